#!/usr/bin/env python3
"""Real plunge mills benchmark: plunges and estimated cycle time with a radial
engagement limit of 0.5 x D and 0.25 x D against the unlimited plan, and the
time stock-aware heights save against retracting to the safe height (a table
for docs/benchmarks.md). Shapes: the test shapes, the examples and, when the README's
main command has run, the FreeCAD demo's operation (out/demo_input.json).

    /usr/bin/python3 tests/bench/bench_mills.py [shape ...]
"""
import argparse
import json
import os
import subprocess
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
CLI = os.path.join(os.environ.get("PLUNGE_BUILD_DIR", os.path.join(ROOT, "build")), "cpp", "plunge-rough")
SHAPES = {name: os.path.join(ROOT, "tests", "data", "shapes", name + ".json")
          for name in ("benchmark", "convex", "concave", "islands", "freeform", "neck")}
SHAPES["example pocket"] = os.path.join(ROOT, "resources", "examples", "pocket.json")
SHAPES["example sculptured"] = os.path.join(ROOT, "resources", "examples", "sculptured.json")
SHAPES["FreeCAD demo"] = os.path.join(ROOT, "out", "demo_input.json")


def plan(path, limit, tmp):
    data = json.load(open(path))
    if data["tools"] == "auto":  # the demo's operation chooses: it plans every plunger of its library
        data["tools"] = data.pop("tool_library")
    if limit:
        for t in data["tools"]:
            t["max_engagement"] = limit * t["diameter"]
    src = os.path.join(os.path.dirname(path), ".bench_mills_input.json")
    with open(src, "w") as f:  # beside the original: a relative floor.brep still resolves
        json.dump(data, f)
    out = os.path.join(tmp, "plan.json")
    try:
        r = subprocess.run([CLI, "plan", src, "-o", out], stderr=subprocess.PIPE, text=True)
    finally:
        os.remove(src)
    if r.returncode == 2:  # refused before planning (limits: max_plunges)
        return None
    r.check_returncode()
    result = json.load(open(out))
    stats = result["stats"]
    plunges = result["plunges"]
    stats["lead_out_share"] = sum("lead_out" in p for p in plunges) / max(1, len(plunges))
    stats["travel_per_plunge"] = stats["travel_length"] / max(1, len(plunges) - 1)
    stats["largest"] = max(t["diameter"] for t in data["tools"])
    return stats


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("shapes", nargs="*", default=list(SHAPES))
    args = ap.parse_args()
    print("| shape | plunges: unlimited / 0.5 D / 0.25 D | row bound 0.5 D / 0.25 D | plunges / bound | "
          "travel per plunge (mm) | lead-outs | minutes: unlimited / 0.5 D / 0.25 D | planning (s) | "
          "saved by stock-aware heights (unlimited) |")
    print("|---|---|---|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        for name in args.shapes:
            if not os.path.exists(SHAPES[name]):
                continue
            runs = [plan(SHAPES[name], limit, tmp) for limit in (None, 0.5, 0.25)]
            free = runs[0]
            # Rows 0.87 D apart, plunges e apart along them (the row pattern), or
            # the unlimited plan where that is more.
            bound = [max(free["plunge_count"], free["region_area"] / (0.87 * free["largest"] * f * free["largest"]))
                     for f in (0.5, 0.25)]
            print("| %s | %s | %s | %s | %s | %s | %s | %s | %.1f min (%.0f %%) |" % (
                name, " / ".join(str(s["plunge_count"]) if s else "refused" for s in runs),
                " / ".join("%.0f" % b for b in bound),
                " / ".join("%.2f" % (s["plunge_count"] / b) if s else "-" for s, b in zip(runs[1:], bound)),
                " / ".join("%.1f" % s["travel_per_plunge"] if s else "-" for s in runs),
                " / ".join("%.0f %%" % (100 * s["lead_out_share"]) if s else "-" for s in runs),
                " / ".join("%.1f" % s["estimated_minutes"] if s else "-" for s in runs),
                " / ".join("%.1f" % s["planning_seconds"] if s else "-" for s in runs),
                free["minutes_at_safe_height"] - free["estimated_minutes"],
                100 * (1 - free["estimated_minutes"] / free["minutes_at_safe_height"])), flush=True)


if __name__ == "__main__":
    main()
