#!/usr/bin/env python3
"""Planning benchmark: plans each test shape with the CLI, several runs each, and
prints the median planning time with the plan's figures (a table for the README).

    /usr/bin/python3 tests/bench/bench_plan.py [--runs 5] [shape ...]
"""
import argparse
import json
import os
import statistics
import subprocess
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
CLI = os.path.join(ROOT, "build", "cpp", "plunge-rough")
SHAPES = os.path.join(ROOT, "tests", "data", "shapes")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("shapes", nargs="*", default=["benchmark", "convex", "concave", "islands", "freeform", "neck"])
    args = ap.parse_args()
    print("| shape | plunges per tool (diameter: count) | plunges / hex reference | coverage | "
          "planning (median of %d) |" % args.runs)
    print("|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        for name in args.shapes:
            out = os.path.join(tmp, name + ".json")
            times, wall = [], []
            for _ in range(args.runs):
                t0 = time.perf_counter()
                subprocess.run([CLI, "plan", os.path.join(SHAPES, name + ".json"), "-o", out], check=True,
                               stderr=subprocess.DEVNULL)
                wall.append(time.perf_counter() - t0)
                times.append(json.load(open(out))["stats"]["planning_seconds"])
            s = json.load(open(out))["stats"]
            tools = ", ".join("%g: %d" % (t["diameter"], t["count"]) for t in s["per_tool"])
            print("| %s | %d (%s) | %.2f | %.2f %% | %.2f s (process %.2f s) |" % (
                name, s["plunge_count"], tools, s["plunge_count"] / s["hex_reference_count"],
                100 * s["coverage"], statistics.median(times), statistics.median(wall)))


if __name__ == "__main__":
    main()
