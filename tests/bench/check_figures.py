"""Compares the figures the pages give with a fresh run of the command printed
beside them, and fails when one has drifted beyond its noise.

    python3 tests/bench/check_figures.py            # runs the Adaptive bench (about a minute)

Checked: docs/benchmarks.md's "Against FreeCAD's Adaptive" tables (every
Plunge Rough time and plunge count, every ratio) and the README's table of
ratios, against tests/bench/bench_vs_adaptive.py. Plunge Rough's plans are
deterministic: its minutes must agree to 0.01 min. Adaptive's paths vary a
little from run to run (FreeCAD 0.20's Adaptive is threaded): pocket 4's
model B ratio came out 1.95, 2.02, 2.02 and 2.11 in four runs, so a ratio
may move by 6 %. And the "Stock left"
tables, every cell but the planning time, against tests/bench/bench_stock.py
(about 20 s; deterministic, so exactly as printed), with the README's plunge
counts of the plate and the sculptured example; and the "Real plunge mills"
table, every cell but the planning time, against tests/bench/bench_mills.py
(its FreeCAD demo row where the README's main command has made
out/demo_input.json). The planning seconds are not checked: they are this
machine's.

    python3 tests/bench/check_figures.py ADAPTIVE_OUTPUT STOCK_OUTPUT   # both saved
"""
import os
import re
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
RATIO_NOISE = 0.06


def fresh_output():
    env = dict(os.environ, XDG_DATA_HOME=tempfile.mkdtemp(), XDG_CONFIG_HOME=tempfile.mkdtemp())
    run = subprocess.run(["freecadcmd", os.path.join(ROOT, "tests", "bench", "bench_vs_adaptive.py")],
                         capture_output=True, text=True, env=env, cwd=ROOT, timeout=1800)
    if "| pocket | model |" not in run.stdout:
        sys.exit("the bench printed no table:\n" + run.stdout[-2000:] + run.stderr[-2000:])
    return run.stdout


def rows(text, header):
    """The rows of the table whose header line starts with `header`, as cell lists."""
    lines = text.splitlines()
    start = next(i for i, l in enumerate(lines) if l.startswith(header))
    out = []
    for line in lines[start + 2:]:
        if not line.startswith("|"):
            break
        out.append([c.strip() for c in line.strip("|").split("|")])
    return out


def number(cell):
    return float(re.match(r"-?[\d.]+", cell).group(0))


def compare(fresh, page, problems):
    """docs/benchmarks.md's two tables against the fresh ones."""
    times = {(r[0], r[1]): r for r in rows(fresh, "| pocket | model |")}
    for r in rows(page, "| pocket | model |"):
        f = times.get((r[0], r[1]))
        if f is None:
            problems.append("benchmarks.md: %s, model %s: not in the fresh run" % (r[0], r[1]))
            continue
        if abs(number(r[2]) - number(f[2])) > 0.011:
            problems.append("benchmarks.md: %s, model %s: Plunge Rough %s min, fresh %s" % (r[0], r[1], r[2], f[2]))
        if abs(number(r[5]) / number(f[5]) - 1) > RATIO_NOISE:
            problems.append("benchmarks.md: %s, model %s: ratio %s, fresh %s" % (r[0], r[1], r[5], f[5]))
    volumes = {r[0]: r for r in rows(fresh, "| pocket | target cm3")}
    for r in rows(page, "| pocket | target cm3"):
        f = volumes.get(r[0])
        if f is None or r[4] != f[4]:  # the plunges per tool and levels, exactly
            problems.append("benchmarks.md: %s: plunges %s, fresh %s" % (r[0], r[4], f[4] if f else "none"))


def pocket_key(name):
    """A pocket by its dimensions ("120 x 80 x 60"), or "demo": the README
    names them more loosely than the bench."""
    m = re.search(r"\d+ x \d+ x \d+", name)
    return m.group(0) if m else ("demo" if "demo" in name else name)


def compare_readme(fresh, readme, problems):
    """The README's ratios (model A, model B) by pocket."""
    ratio = {(pocket_key(r[0]), r[1]): number(r[5]) for r in rows(fresh, "| pocket | model |")}
    for r in rows(readme, "| pocket | Plunge Rough / Adaptive"):
        for model, cell in (("A", r[1]), ("B", r[2])):
            key = (pocket_key(r[0]), model)
            if key not in ratio:
                problems.append("README: %s: not in the fresh run" % r[0])
            elif abs(number(cell) / ratio[key] - 1) > RATIO_NOISE + 0.01:  # the README rounds to 0.01
                problems.append("README: %s, model %s: %s, fresh %.3f" % (r[0], model, cell, ratio[key]))


STOCK_TABLES = ["| shape | plan | plunges |", "| floor | floor-stock step |"]


def fresh_stock():
    run = subprocess.run(["/usr/bin/python3", os.path.join(ROOT, "tests", "bench", "bench_stock.py")],
                         capture_output=True, text=True, cwd=ROOT, timeout=600)
    if run.returncode != 0 or STOCK_TABLES[0] not in run.stdout:
        sys.exit("the stock bench failed:\n" + run.stdout[-2000:] + run.stderr[-2000:])
    return run.stdout


MILLS_TABLE = "| shape | plunges: unlimited"


def fresh_mills():
    run = subprocess.run(["/usr/bin/python3", os.path.join(ROOT, "tests", "bench", "bench_mills.py")],
                         capture_output=True, text=True, cwd=ROOT, timeout=900)
    if run.returncode != 0 or MILLS_TABLE not in run.stdout:
        sys.exit("the mills bench failed:\n" + run.stdout[-2000:] + run.stderr[-2000:])
    return run.stdout


def compare_mills(fresh, page, problems):
    """Row by row, every cell but the planning seconds (the 8th); the FreeCAD
    demo's row only where the bench could plan it (out/demo_input.json)."""
    table = {r[0]: r for r in rows(fresh, MILLS_TABLE)}
    for r in rows(page, MILLS_TABLE):
        f = table.get(r[0])
        if f is None and r[0] == "FreeCAD demo":
            print("FreeCAD demo's row not checked: run the README's main command first (out/demo_input.json)")
            continue
        if f is None or f[:7] + f[8:] != r[:7] + r[8:]:
            problems.append("benchmarks.md: %s: %s, fresh %s" % (r[0], r[1:7] + r[8:], f[1:7] + f[8:] if f else "none"))


def compare_stock(fresh, page, readme, problems):
    """The stock tables, row by row (shape and plan), every cell but the last
    (the planning time); and the README's plunge counts of the plate and the
    sculptured example, which are the tables' 1 mm band and 1 mm floor-stock rows."""
    for header in STOCK_TABLES:
        table = {tuple(r[:2]): r for r in rows(fresh, header)}
        for r in rows(page, header):
            f = table.get(tuple(r[:2]))
            if f is None or f[:-1] != r[:-1]:
                problems.append("benchmarks.md: %s, %s: %s, fresh %s" % (r[0], r[1], r[2:-1], f[2:-1] if f else "none"))
    counts = {r[0]: r[2] for r in rows(fresh, STOCK_TABLES[0]) if r[1] == "1 mm band"}
    counts.update({r[0]: r[2].split()[0] for r in rows(fresh, STOCK_TABLES[1]) if r[1] == "1 mm"})
    for r in rows(readme, "| planning | plunges |"):
        key = ("benchmark" if "600 x 400" in r[0] else
               "example sculptured (expression)" if "example's sculptured" in r[0] else None)
        if key and counts.get(key) != r[1]:
            problems.append("README: %s: %s plunges, fresh %s" % (r[0], r[1], counts.get(key)))


def main():
    adaptive = open(sys.argv[1]).read() if len(sys.argv) > 1 else fresh_output()
    stock = open(sys.argv[2]).read() if len(sys.argv) > 2 else fresh_stock()
    problems = []
    page = open(os.path.join(ROOT, "docs", "benchmarks.md")).read()
    readme = open(os.path.join(ROOT, "README.md")).read()
    compare(adaptive, page, problems)
    compare_readme(adaptive, readme, problems)
    compare_stock(stock, page, readme, problems)
    compare_mills(fresh_mills(), page, problems)
    for p in problems:
        print(p)
    print("figures checked against a fresh run: %s" % ("all hold" if not problems else "%d drifted" % len(problems)))
    sys.exit(1 if problems else 0)


if __name__ == "__main__":
    main()
