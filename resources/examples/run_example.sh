#!/bin/sh
# The main job. Installs what is missing (Debian packages, FreeCAD included),
# builds, installs the FreeCAD addon into FreeCAD's user Mod folder, then:
#  1. plans the bundled pocket with the command-line tool: out/plan.json, .svg, .nc;
#  2. runs the headless FreeCAD demo with the installed addon (example part with a
#     free-form wall, island and sculptured floor; Job with three plungers; Plunge
#     Rough; linuxcnc post): out/plunge_rough.ngc, .svg, summary.txt, the document.
set -eu
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
sh "$ROOT/resources/setup.sh"
sh "$ROOT/resources/install_addon.sh"
mkdir -p "$ROOT/out"

"$ROOT/build/cpp/plunge-rough" plan "$ROOT/resources/examples/pocket.json" \
  -o "$ROOT/out/plan.json" --svg "$ROOT/out/plan.svg" --gcode "$ROOT/out/plan.nc"
/usr/bin/python3 - "$ROOT/out/plan.json" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))["stats"]
print("command line, resources/examples/pocket.json:")
print("  plunges: %d (%s)" % (s["plunge_count"], ", ".join(
    "T%d %g mm: %d" % (t["tool_id"], t["diameter"], t["count"]) for t in s["per_tool"])))
print("  coverage of the accessible area: %.2f %%" % (100 * s["coverage"]))
print("  travel between plunges: %.0f mm, planned in %.2f s" % (s["travel_length"], s["planning_seconds"]))
print("  wrote out/plan.json, out/plan.svg, out/plan.nc")
PY

echo "FreeCAD, resources/examples/freecad_demo.py:"
cd "$ROOT/out"
PLUNGE_OUT="$ROOT/out" PLUNGE_EXAMPLES="$ROOT/resources/examples" \
  freecadcmd -c "exec(open('$ROOT/resources/examples/freecad_demo.py').read())" 2>&1 \
  | tr '\r' '\n' | grep -iv '^\s*$\|%)\|^Recompute\|^Importing\|^Show editor\|postprocessing' || true
test -s "$ROOT/out/plunge_rough.ngc" || { echo "run_example: the FreeCAD demo wrote no G-code" >&2; exit 1; }
