#!/bin/sh
# The main job on the bundled example pocket: writes out/plan.json, out/plan.svg
# and out/plan.nc, and prints a short summary.
set -eu
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
sh "$ROOT/resources/setup.sh"
mkdir -p "$ROOT/out"
"$ROOT/build/cpp/plunge-rough" plan "$ROOT/resources/examples/pocket.json" \
  -o "$ROOT/out/plan.json" --svg "$ROOT/out/plan.svg" --gcode "$ROOT/out/plan.nc"
/usr/bin/python3 - "$ROOT/out/plan.json" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))["stats"]
print("plunges: %d (%s)" % (s["plunge_count"], ", ".join(
    "T%d %g mm: %d" % (t["tool_id"], t["diameter"], t["count"]) for t in s["per_tool"])))
print("coverage of the accessible area: %.2f %%" % (100 * s["coverage"]))
print("travel between plunges: %.0f mm, planned in %.2f s" % (s["travel_length"], s["planning_seconds"]))
PY
echo "wrote out/plan.json, out/plan.svg, out/plan.nc"
