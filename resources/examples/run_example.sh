#!/bin/sh
# The main job. Installs what is missing (Debian packages, FreeCAD included),
# builds, installs the FreeCAD addon into FreeCAD's user Mod folder, then:
#  1. plans the bundled pocket with the command-line tool: out/plan.json, .svg, .nc;
#  2. runs the FreeCAD demo with the installed addon in FreeCAD's GUI on a virtual
#     display, so that the document is one a user would have made (example part
#     with a free-form wall, island and sculptured floor; Job with three plungers;
#     Plunge Rough; linuxcnc post): out/plunge_rough.ngc, .svg, summary.txt, the
#     document; then the second demo, a 75 mm deep die pocket where plunging
#     pays: out/deep_pocket.ngc, .svg, deep_pocket_summary.txt, .FCStd.
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

echo "FreeCAD, resources/examples/freecad_demo.py (FreeCAD's GUI on a virtual display):"
rm -f "$ROOT/out/summary.txt" "$ROOT/out/plunge_rough.ngc" "$ROOT/out/demo_error.txt" "$ROOT/out/deep_pocket_summary.txt"
cd "$ROOT/out"
# QtWebEngine (FreeCAD's start page) refuses to start as root without this.
PLUNGE_OUT="$ROOT/out" PLUNGE_EXAMPLES="$ROOT/resources/examples" QTWEBENGINE_DISABLE_SANDBOX=1 QT_QPA_PLATFORM=xcb \
  timeout 600 xvfb-run -a -s "-screen 0 1600x1000x24" freecad "$ROOT/resources/examples/freecad_demo.py" \
  >"$ROOT/out/freecad.log" 2>&1 || true
if [ -s "$ROOT/out/demo_error.txt" ] || [ ! -s "$ROOT/out/summary.txt" ] || [ ! -s "$ROOT/out/deep_pocket_summary.txt" ]; then
  echo "run_example: the FreeCAD demo failed (out/freecad.log):" >&2
  cat "$ROOT/out/demo_error.txt" >&2 2>/dev/null || tail -n 20 "$ROOT/out/freecad.log" >&2
  exit 1
fi
cat "$ROOT/out/summary.txt"
echo
cat "$ROOT/out/deep_pocket_summary.txt"
echo "wrote $ROOT/out: plunge_rough.ngc, plunge_rough.svg (-stock, -heights: the stock left, the stop heights), summary.txt, plunge_example.FCStd, bits/;"
echo "  the deep pocket: deep_pocket.ngc, deep_pocket.svg, deep_pocket-stock.svg, deep_pocket_summary.txt, deep_pocket.FCStd"
