#!/usr/bin/env python3
"""Big boundaries: planning time against the boundary's vertex count (a table
for docs/benchmarks.md). The boundary is a smooth closed curve of about 600 x 400 mm
(a B-spline face's outline at a finer and finer chordal tolerance), plunged
with 12 and 6 mm tools, 0.5 mm radial allowance; times are the command-line
tool's whole run, best of three.

    /usr/bin/python3 tests/bench/bench_boundary.py [vertices ...]
"""
import json
import math
import os
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
CLI = os.path.join(ROOT, "build", "cpp", "plunge-rough")


def free_form(n):
    pts = []
    for i in range(n):
        t = 2 * math.pi * i / n
        r = (1 + 0.15 * math.sin(3 * t) + 0.08 * math.cos(5 * t)) / 1.23
        pts.append([300 + 290 * r * math.cos(t), 200 + 190 * r * math.sin(t)])
    return {"version": 1, "boundary": pts, "tools": [{"diameter": 12, "id": 1}, {"diameter": 6, "id": 2}],
            "top_z": 0, "safe_z": 5, "floor": {"z": -20}, "allowance": {"radial": 0.5}, "seed": 1}


def main():
    counts = [int(a) for a in sys.argv[1:]] or [1000, 3000, 10000, 30000, 100000, 300000]
    print("| vertices | plunges | walls simplified by | time |")
    print("|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        for n in counts:
            src, out = os.path.join(tmp, "in.json"), os.path.join(tmp, "plan.json")
            with open(src, "w") as f:
                json.dump(free_form(n), f)
            best = math.inf
            for _ in range(3):
                t0 = time.perf_counter()
                subprocess.run([CLI, "plan", src, "-o", out], check=True, stderr=subprocess.DEVNULL)
                best = min(best, time.perf_counter() - t0)
            s = json.load(open(out))["stats"]
            print("| %d | %d | %.3f mm | %.2f s |" % (n, s["plunge_count"], s["boundary_tolerance"], best), flush=True)


if __name__ == "__main__":
    main()
