#!/usr/bin/env python3
"""Responsiveness benchmark: plans each input with a progress callback and
prints the longest time between two calls of it, and in which stage, per input
(what a user waits for after pressing Esc). The planner's promise: at most 0.5 s
of work between calls, so a cancel stops it within 1 s.

    /usr/bin/python3 tests/bench/bench_progress.py [--build build] [--program PATH] [input.json ...]

--program: the planner program as FreeCAD's addon runs it (plunge-rough call,
e.g. a bundle's), the gaps between the progress lines it writes on stderr.

Without inputs: the test shapes, the examples, each with its tools limited to
0.25 D, and the sculptured example with the floor fillet's corner blend.
"""
import argparse
import copy
import json
import os
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SHAPES = os.path.join(ROOT, "tests", "data", "shapes")
EXAMPLES = os.path.join(ROOT, "resources", "examples")


def inputs(paths):
    if paths:
        for p in paths:
            yield os.path.basename(p), json.load(open(p)), os.path.dirname(os.path.abspath(p))
        return
    for folder, names in ((SHAPES, ["benchmark", "convex", "concave", "islands", "freeform", "neck"]),
                          (EXAMPLES, ["pocket", "sculptured"])):
        for name in names:
            data = json.load(open(os.path.join(folder, name + ".json")))
            yield name, data, folder
            limited = copy.deepcopy(data)
            for t in limited["tools"]:
                t["max_engagement"] = 0.25 * t["diameter"]
            yield name + " 0.25 D", limited, folder


def measure(plunge, data):
    """Longest gap between progress calls (s), its stage, and the plan's time."""
    calls = []

    def progress(fraction, stage):
        calls.append((time.perf_counter(), stage))
        return True

    t0 = time.perf_counter()
    calls.append((t0, "start"))
    plunge.plan(data, svg=False, progress=progress)
    calls.append((time.perf_counter(), "end"))
    gap, stage = max((b[0] - a[0], a[1]) for a, b in zip(calls, calls[1:]))
    return gap, stage, calls[-1][0] - t0


def measure_program(program, data):
    """The same for the program: the longest gap between its progress lines."""
    import subprocess
    t0 = time.perf_counter()
    proc = subprocess.Popen([program, "call"], stdin=subprocess.PIPE, stdout=subprocess.DEVNULL,
                            stderr=subprocess.PIPE)
    proc.stdin.write(json.dumps({"call": "plan", "input": data}).encode())
    proc.stdin.close()
    calls = [(t0, "start")]
    for line in proc.stderr:
        calls.append((time.perf_counter(), line.decode().split(" ", 2)[-1].strip()))
    proc.wait()
    calls.append((time.perf_counter(), "end"))
    gap, stage = max((b[0] - a[0], a[1]) for a, b in zip(calls, calls[1:]))
    return gap, stage, calls[-1][0] - t0


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--program", help="measure this planner program's progress lines instead of the module")
    ap.add_argument("inputs", nargs="*")
    args = ap.parse_args()
    sys.path.insert(0, os.path.join(args.build, "cpp"))
    import plunge
    program = os.path.abspath(args.program) if args.program else None
    print("| input | planning | longest gap between progress calls | in stage |")
    print("|---|---|---|---|")
    worst = 0.0
    for name, data, folder in inputs(args.inputs):
        os.chdir(folder)  # relative BREP floors
        if program:
            gap, stage, total = measure_program(program, data)
        else:
            gap, stage, total = measure(plunge, data)
        worst = max(worst, gap)
        print("| %s | %.2f s | %.3f s | %s |" % (name, total, gap, stage), flush=True)
    print("\nworst gap: %.3f s" % worst)


if __name__ == "__main__":
    main()
