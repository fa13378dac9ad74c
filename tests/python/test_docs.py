"""The front page and docs/: the README is a front page (two commands first,
short), and every link and picture of it and of docs/ leads somewhere."""
import os
import re

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
DOCS = os.path.join(ROOT, "docs")
PAGES = [os.path.join(ROOT, "README.md")] + sorted(
    os.path.join(DOCS, f) for f in os.listdir(DOCS) if f.endswith(".md"))
LINK = re.compile(r"!?\[[^\]]*\]\(([^)\s]+)\)")


def anchors(path):
    """GitHub's anchors of a page's headings: lower case, punctuation dropped, spaces as dashes."""
    out = set()
    for line in open(path).read().splitlines():
        m = re.match(r"#+ (.*)", line)
        if m:
            out.add(re.sub(r"[^\w\- ]", "", m.group(1).strip().lower()).replace(" ", "-"))
    return out


def outside_code(text):
    return re.sub(r"```.*?```", "", text, flags=re.S)


def test_every_link_and_picture_leads_somewhere():
    broken = []
    for page in PAGES:
        for target in LINK.findall(outside_code(open(page).read())):
            if re.match(r"[a-z]+://", target):
                continue
            path, _, anchor = target.partition("#")
            where = os.path.normpath(os.path.join(os.path.dirname(page), path)) if path else page
            if not os.path.exists(where):
                broken.append((os.path.relpath(page, ROOT), target))
            elif anchor and where.endswith(".md") and anchor not in anchors(where):
                broken.append((os.path.relpath(page, ROOT), target + " (no such heading)"))
    assert not broken, broken


def test_the_readme_is_a_front_page():
    text = open(os.path.join(ROOT, "README.md")).read()
    lines = text.splitlines()
    assert len(lines) <= 250, len(lines)
    # The two commands come first (tests/fresh/run.sh runs exactly these).
    block = text.split("```sh\n", 1)[1].split("```", 1)[0]
    assert [l.split("#")[0].strip() for l in block.strip().splitlines()] == [
        "sh resources/examples/run_example.sh", "sh tests/run.sh"]
    assert text.index("```sh") < 400
    # What it is, with a picture, on the first screen (about 50 lines).
    first = "\n".join(lines[:50])
    assert "plunge" in first.lower() and "FreeCAD" in first and "![" in first
    # Every page of docs/ is linked from the front page.
    linked = {os.path.normpath(t.partition("#")[0]) for t in LINK.findall(text)}
    missing = [f for f in os.listdir(DOCS) if f.endswith(".md") and os.path.join("docs", f) not in linked]
    assert not missing, missing


def test_every_doc_picture_is_made_again_by_the_gui_test():
    """docs/images/ holds only what tests/freecad/refresh_doc_images.sh copies
    from the GUI test's artifacts, each once: no picture there goes stale
    without a way to make it again."""
    script = open(os.path.join(ROOT, "tests", "freecad", "refresh_doc_images.sh")).read()
    table = script.split("<<'MAP'\n", 1)[1].split("\nMAP\n", 1)[0]
    names = [line.split()[0] for line in table.splitlines() if line.strip()]
    assert len(names) == len(set(names)), names
    assert sorted(names) == sorted(os.listdir(os.path.join(ROOT, "docs", "images")))
