#!/usr/bin/env python3
"""The automatic tool choice against the plan of the whole library and against
every tool set planned in full that reaches what the library's smallest must
cut (its smallest at most the choice's smallest candidate): planning time (min of --runs, with the plans'
own planning_seconds), the set chosen, its minutes, the library's and the best
set's. Each test shape and the FreeCAD demo (out/demo_input.json, after the
README's main command), with the shapes' own feeds and with every feed at
1200 mm/min (plunge mills: tool changes then weigh more).

    /usr/bin/python3 tests/bench/bench_choice.py [--runs 3] [--build build]
"""
import argparse
import itertools
import json
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SHAPES = {name: os.path.join(ROOT, "tests", "data", "shapes", name + ".json")
          for name in ("benchmark", "convex", "concave", "islands", "freeform", "neck")}
SHAPES["FreeCAD demo"] = os.path.join(ROOT, "out", "demo_input.json")


def fastest(plunge, data, runs):
    best = None
    for _ in range(runs):
        plan = plunge.plan(data)
        if best is None or plan["stats"]["planning_seconds"] < best["stats"]["planning_seconds"]:
            best = plan
    return best


def every_set(plunge, data, reach):
    """Minutes of every subset of the library whose smallest tool is at most
    `reach` (the choice's smallest candidate, which reaches all the library's
    smallest must cut), planned in full; a set that cannot be planned left out."""
    tools = sorted(data["tools"], key=lambda t: -t["diameter"])
    out = {}
    for k in range(1, len(tools) + 1):
        for sub in itertools.combinations(tools, k):
            if sub[-1]["diameter"] > reach:
                continue
            try:
                stats = plunge.plan(dict(data, tools=list(sub)))["stats"]
            except ValueError:
                continue
            out[tuple(t["diameter"] for t in sub)] = stats["estimated_minutes"]
    return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    args = ap.parse_args()
    sys.path.insert(0, os.path.join(os.path.abspath(args.build), "cpp"))
    import plunge
    print("| shape | feeds | one plan s | choice s | ratio | chosen | min | library min | best set min |")
    print("|---|---|---|---|---|---|---|---|---|")
    for name, path in SHAPES.items():
        if not os.path.exists(path):
            print("(%s: %s is missing, skipped)" % (name, os.path.relpath(path, ROOT)))
            continue
        base = json.load(open(path))
        if base["tools"] == "auto":  # an operation's input: its plungers are the library
            base["tools"] = base.pop("tool_library")
        if "brep" in base["floor"] and not os.path.isabs(base["floor"]["brep"]):
            base["floor"]["brep"] = os.path.join(os.path.dirname(path), base["floor"]["brep"])
        for feeds in ("own", "1200"):
            data = json.loads(json.dumps(base))
            if feeds == "1200":
                for t in data["tools"]:
                    t["feed"] = 1200.0
            one = fastest(plunge, data, args.runs)
            auto = fastest(plunge, dict(data, tools="auto", tool_library=data["tools"]), args.runs)
            sets = every_set(plunge, data, auto["tool_selection"]["candidates"][-1])
            t1, t2 = one["stats"]["planning_seconds"], auto["stats"]["planning_seconds"]
            print("| %s | %s | %.2f | %.2f | %.2f | %s | %.2f | %.2f | %.2f (%s) |" % (
                name, feeds, t1, t2, t2 / t1, "/".join("%g" % d for d in auto["tool_selection"]["chosen"]),
                auto["stats"]["estimated_minutes"], one["stats"]["estimated_minutes"], min(sets.values()),
                "/".join("%g" % d for d in min(sets, key=sets.get))), flush=True)


if __name__ == "__main__":
    main()
