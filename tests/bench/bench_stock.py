#!/usr/bin/env python3
"""The stock a plan leaves (docs/benchmarks.md, "Stock left"): for every test shape and
example, the plan with the default 1 mm wall band against the honeycomb grid of
the same tools and against covering to 99.6 % (max_wall_stock 0): plunges, core
coverage, thickest wall stock; then the sculptured floors with and without the
floor-stock step in Z (max_floor_stock 1 mm): floor stock, volume left, plunges added.

    /usr/bin/python3 tests/bench/bench_stock.py     # PLUNGE_BUILD_DIR: another build tree
"""
import json
import os
import subprocess
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
CLI = os.path.join(os.environ.get("PLUNGE_BUILD_DIR", os.path.join(ROOT, "build")), "cpp", "plunge-rough")
SHAPES = os.path.join(ROOT, "tests", "data", "shapes")
EXAMPLES = os.path.join(ROOT, "resources", "examples")


def run(data, tmp, base_dir):
    src, out = os.path.join(base_dir, ".bench_in.json"), os.path.join(tmp, "out.json")
    with open(src, "w") as f:
        json.dump(data, f)
    try:
        subprocess.run([CLI, "plan", src, "-o", out], check=True, stdout=subprocess.DEVNULL,
                       stderr=subprocess.DEVNULL)
    finally:
        os.remove(src)
    with open(out) as f:
        return json.load(f)["stats"]


def load(path):
    with open(path) as f:
        return json.load(f)


def main():
    cases = [(n, os.path.join(SHAPES, n + ".json"))
             for n in ["benchmark", "convex", "concave", "islands", "freeform", "neck"]]
    cases += [("example pocket", os.path.join(EXAMPLES, "pocket.json"))]
    print("| shape | plan | plunges | core cut | thickest wall stock | planning |")
    print("|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        for name, path in cases:
            base = load(path)
            for label, extra in [("1 mm band", {"max_wall_stock": 1.0}),
                                 ("honeycomb grid", {"strategy": "grid", "grid": {"pattern": "honeycomb"}}),
                                 ("99.6 % coverage (band 0)", {"max_wall_stock": 0})]:
                s = run(dict(base, max_floor_stock=0, **extra), tmp, os.path.dirname(path))
                print("| %s | %s | %d | %.3f %% | %.2f mm | %.2f s |" % (
                    name, label, s["plunge_count"], 100 * s["core_coverage"], s["max_wall_stock_left"],
                    s["planning_seconds"]))
        print()
        print("| floor | floor-stock step | plunges (added) | floor stock max / mean | volume left | planning |")
        print("|---|---|---|---|---|---|")
        floors = [("example sculptured (expression)", os.path.join(EXAMPLES, "sculptured.json"), {})]
        brep = os.path.join(ROOT, "tests", "data", "floors", "bumps.brep")
        if os.path.exists(brep):
            floors.append(("BREP bumps", os.path.join(ROOT, "tests", "data", "floors", "bumps.brep"),
                           {"boundary": [[2, 2], [98, 2], [98, 73], [2, 73]],
                            "islands": [[[40, 20], [55, 20], [48, 34]]],
                            "tools": [{"diameter": 12}, {"diameter": 6}], "top_z": 0, "safe_z": 5,
                            "floor": {"brep": "bumps.brep"}, "allowance": {"radial": 0.5, "floor": 0.3}}))
        for name, path, data in floors:
            base = data or load(path)
            for label, limit in [("off (max_floor_stock 0)", 0), ("1 mm", 1.0)]:
                s = run(dict(base, max_floor_stock=limit), tmp, os.path.dirname(path))
                print("| %s | %s | %d (%d) | %.2f / %.2f mm | %.1f cm³ | %.2f s |" % (
                    name, label, s["plunge_count"], s["floor_stock_plunges"], s["max_floor_stock_left"],
                    s["mean_floor_stock"], s["volume_left"] / 1000, s["planning_seconds"]))


if __name__ == "__main__":
    main()
