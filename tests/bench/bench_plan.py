#!/usr/bin/env python3
"""Planning benchmark: plans each test shape with the CLI, several runs each, and
prints the median planning time with the plan's figures (a table for docs/benchmarks.md),
beside the figure recorded the last time (tests/bench/plan_figures.json), so a
regression shows. Sculptured floors: the example and, when the README's main
command has run, the FreeCAD demo's operation (out/demo_input.json); with
--each-tool also each of their tools alone.

    /usr/bin/python3 tests/bench/bench_plan.py [--runs 5] [--each-tool] [--record] [shape ...]

--record writes this run's medians to plan_figures.json (do it on an idle
machine, and say so in the commit).
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
FIGURES = os.path.join(ROOT, "tests", "bench", "plan_figures.json")
SHAPES = {name: os.path.join(ROOT, "tests", "data", "shapes", name + ".json")
          for name in ("benchmark", "convex", "concave", "islands", "freeform", "neck")}
SHAPES["example sculptured"] = os.path.join(ROOT, "resources", "examples", "sculptured.json")
SHAPES["FreeCAD demo"] = os.path.join(ROOT, "out", "demo_input.json")


def plan(data, src_dir, tmp):
    """Planning seconds (the plan's own, and the process's) and the plan's stats."""
    src = os.path.join(src_dir, ".bench_plan_input.json")
    out = os.path.join(tmp, "plan.json")
    with open(src, "w") as f:  # beside the original: a relative floor.brep still resolves
        json.dump(data, f)
    try:
        t0 = time.perf_counter()
        subprocess.run([CLI, "plan", src, "-o", out], check=True, stderr=subprocess.DEVNULL)
        wall = time.perf_counter() - t0
    finally:
        os.remove(src)
    stats = json.load(open(out))["stats"]
    return stats["planning_seconds"], wall, stats


def cases(names, each_tool):
    """(label, input, folder) per shape, and per tool alone where asked."""
    for name in names:
        path = SHAPES[name]
        if not os.path.exists(path):
            print("(%s: %s is missing, skipped)" % (name, os.path.relpath(path, ROOT)))
            continue
        data = json.load(open(path))
        yield name, data, os.path.dirname(path)
        # An operation's input chooses from its plungers ("auto"): each alone too.
        tools = data["tool_library"] if data.get("tools") == "auto" else data.get("tools")
        if each_tool and isinstance(tools, list) and len(tools) > 1:
            alone_base = {k: v for k, v in data.items() if k != "tool_library"}
            for tool in tools:
                alone = dict(alone_base, tools=[tool])
                yield "%s, %g mm alone" % (name, tool["diameter"]), alone, os.path.dirname(path)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--each-tool", action="store_true")
    ap.add_argument("--record", action="store_true")
    ap.add_argument("shapes", nargs="*", default=list(SHAPES))
    args = ap.parse_args()
    recorded = json.load(open(FIGURES)) if os.path.exists(FIGURES) else {}
    print("| shape | plunges per tool (diameter: count) | plunges / hex reference | coverage | "
          "planning (median of %d) | recorded before |" % args.runs)
    print("|---|---|---|---|---|---|")
    figures = dict(recorded)
    with tempfile.TemporaryDirectory() as tmp:
        for label, data, folder in cases(args.shapes, args.each_tool):
            runs = [plan(data, folder, tmp) for _ in range(args.runs)]
            seconds = statistics.median(r[0] for r in runs)
            wall = statistics.median(r[1] for r in runs)
            s = runs[-1][2]
            tools = ", ".join("%g: %d" % (t["diameter"], t["count"]) for t in s["per_tool"])
            before = recorded.get(label)
            print("| %s | %d (%s) | %.2f | %.2f %% | %.2f s (process %.2f s) | %s |" % (
                label, s["plunge_count"], tools, s["plunge_count"] / s["hex_reference_count"],
                100 * s["coverage"], seconds, wall, "%.2f s" % before if before is not None else "-"))
            figures[label] = round(seconds, 3)
    if args.record:
        with open(FIGURES, "w") as f:
            json.dump(figures, f, indent=1, sort_keys=True)
            f.write("\n")


if __name__ == "__main__":
    main()
