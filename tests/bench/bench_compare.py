#!/usr/bin/env python3
"""Packing against the grid baseline: plans every test shape with packing and
with the square and honeycomb grids (same tools, same time model) and prints,
side by side, plunges per tool, coverage, travel, estimated time and planning
time; then the automatic tool choice per shape from a library (a table each for
docs/benchmarks.md).

    /usr/bin/python3 tests/bench/bench_compare.py [shape ...]
"""
import argparse
import json
import os
import subprocess
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
CLI = os.path.join(ROOT, "build", "cpp", "plunge-rough")
SHAPES = os.path.join(ROOT, "tests", "data", "shapes")
LIBRARY = [{"diameter": d, "id": i + 1, "feed": f}
           for i, (d, f) in enumerate([(32, 120), (25, 150), (20, 150), (16, 180), (12, 200), (8, 250), (6, 300)])]


def run(data, tmp):
    src, out = os.path.join(tmp, "in.json"), os.path.join(tmp, "out.json")
    with open(src, "w") as f:
        json.dump(data, f)
    subprocess.run([CLI, "plan", src, "-o", out], check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    with open(out) as f:
        return json.load(f)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("shapes", nargs="*", default=["benchmark", "convex", "concave", "islands", "freeform", "neck"])
    args = ap.parse_args()
    print("| shape | strategy | plunges (per tool) | coverage | travel | est. time | planning |")
    print("|---|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        for name in args.shapes:
            with open(os.path.join(SHAPES, name + ".json")) as f:
                base = json.load(f)
            runs = [("packing (1 mm band)", {}), ("grid square", {"strategy": "grid", "grid": {"pattern": "square"}}),
                    ("grid honeycomb", {"strategy": "grid", "grid": {"pattern": "honeycomb"}}), None]
            best_grid = 0.0
            for run_ in runs:
                if run_ is None:  # packing stopped at the better grid's coverage: equal coverage
                    run_ = ("packing at %.2f %% (no band)" % (100 * best_grid),
                            {"min_coverage": best_grid, "max_wall_stock": 0})
                label, extra = run_
                s = run(dict(base, **extra), tmp)["stats"]
                if label.startswith("grid"):
                    best_grid = max(best_grid, s["coverage"])
                tools = ", ".join("%g: %d" % (t["diameter"], t["count"]) for t in s["per_tool"])
                print("| %s | %s | %d (%s) | %.2f %% | %.0f mm | %.1f min | %.2f s |" % (
                    name, label, s["plunge_count"], tools, 100 * s["coverage"], s["travel_length"],
                    s["estimated_minutes"], s["planning_seconds"]))
        print()
        print("Automatic choice from the library %s (diameter/feed mm/min):" % ", ".join(
            "%g/%g" % (t["diameter"], t["feed"]) for t in LIBRARY))
        print()
        print("| shape | necks (width) | candidates | sets estimated / pruned | chosen | plunges | est. time | "
              "planning |")
        print("|---|---|---|---|---|---|---|---|")
        for name in args.shapes:
            with open(os.path.join(SHAPES, name + ".json")) as f:
                base = json.load(f)
            data = dict(base, tools="auto", tool_library=LIBRARY)
            plan = run(data, tmp)
            sel, s = plan["tool_selection"], plan["stats"]
            # Sets placed and estimated (one of them then planned in full), and pruned by the bound.
            estimated = sum(1 for x in sel["sets"] if "plunges" in x)
            pruned = sum(1 for x in sel["sets"] if "pruned" in x)
            necks = ", ".join("%.1f" % n["width"] for n in sel["necks"]) or "none"
            print("| %s | %s | %s | %d / %d | %s | %d | %.1f min | %.2f s |" % (
                name, necks, "/".join("%g" % d for d in sel["candidates"]), estimated, pruned,
                "/".join("%g" % d for d in sel["chosen"]), s["plunge_count"], s["estimated_minutes"],
                s["planning_seconds"]))


if __name__ == "__main__":
    main()
