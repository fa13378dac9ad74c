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


# What the planner can say (docs/troubleshooting.md, "Limits a plan cannot
# keep"): each phrase is in the planner's source and on the page, so that a
# line of the report view leads to its row. The phrases are the messages'
# fixed words; the reasons ("why") after the worst place are listed too.
SAID = [
    "places the plunges of",
    "plunges cut a wider band than their tool's max engagement",
    "plunges cut a narrower band than their tool's min engagement",
    "plunges of a non-centre-cutting tool have material under the core",
    "plunges cut deeper than their tool's flute length",
    "mm of stock stay above the floor, more than the",
    "mm from the walls uncut",
    "mm of stock stay on the walls, more than the",
    "% of the reachable floor, less than the",
    "tools too large for the pocket, not used: ",
    "the depth search ran out of its budget on",
    "no stick_out is given: what holds it is not checked",
    "the floor rises and falls faster than the plungers follow",
    "the final depth stops plunges above the floor",
    "no plunger of the job fits there down to that height",
    "the walls lean in below that height",
    "slivers between the plunges along the walls",
    "no plunger of the job reaches there",
    "finer than any plunger or depth search can follow",
    "part material overhangs the pocket above its floor",
    "it also parts the pocket",
    "the part hangs over the whole floor",
    "measured against the whole part",
    "the part there is narrower above the floor than the pocket's outline shows",
]
# The places in cpp/src that say something (Said::warn, Said::limit, the
# motion's counts): a new one needs its phrase above and its row on the page.
SAYING = re.compile(r"\.(?:warn|limit)\(|_\.say\(")
SAYING_PLACES = 17


def planner_source():
    """cpp/src's text with adjacent string literals joined ("a" "b" -> "ab")."""
    src = os.path.join(ROOT, "cpp", "src")
    text = "".join(open(os.path.join(src, f)).read() for f in sorted(os.listdir(src)) if f.endswith(".cpp"))
    return re.sub(r'"\s*\n\s*"', "", text)


def test_every_warning_of_the_planner_has_its_troubleshooting_row():
    source = planner_source()
    page = open(os.path.join(DOCS, "troubleshooting.md")).read()
    assert [p for p in SAID if p not in source] == [], "no longer said by the planner: update SAID and the page"
    assert [p for p in SAID if p not in page] == [], "said by the planner, missing from docs/troubleshooting.md"
    places = [f for f in sorted(os.listdir(os.path.join(ROOT, "cpp", "src")))
              if f.endswith(".cpp") and f != "broken.cpp"
              for _ in SAYING.finditer(open(os.path.join(ROOT, "cpp", "src", f)).read())]
    assert len(places) == SAYING_PLACES, (
        "the planner says something in a new place (%s): give it a row in docs/troubleshooting.md and its phrase "
        "in SAID, then count it here" % sorted(set(places)))
