"""A tray like NIST's (issue: floor rest on filleted floors): a 280 x 194 mm
pocket 30 mm deep in a block, its walls rounded R12 and its floor edges
filleted R6 (Part booleans and fillets, as a user models it); the floor face
selected, fillets included (the default), 12/8/5 mm flat plungers from .fctb
bits, Max Floor Stock 1 mm, allowances 0.5 mm radial and 0.3 mm floor. Timed
as users get it: the recompute through the README's install (the module, the
floor as BREP faces) and through the Linux bundle's program (the floor as a
mesh), with the plans' plunges, floor-stock plunges and the floor stock they leave.

    sh resources/bundle.sh linux
    XDG_DATA_HOME=$(mktemp -d) XDG_CONFIG_HOME=$(mktemp -d) freecadcmd tests/bench/bench_tray.py

PLUNGE_BENCH_REPEAT (default 3) sets the repeats (the median is given)."""
import os
import statistics
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path[:0] = [ROOT, os.path.join(ROOT, "build", "cpp"), os.path.join(ROOT, "resources", "examples"),
                os.path.dirname(os.path.abspath(__file__)), os.path.join(ROOT, "tests", "freecad")]

import FreeCAD  # noqa: E402

from example_part import add_plunge_rough, make_job  # noqa: E402
from parts import tray, tray_floor  # noqa: E402
from both_planners import PLANNERS, bundle_program, recompute_timed  # noqa: E402
from freecad_plugin import PlungeRough, planner  # noqa: E402

REPEAT = int(os.environ.get("PLUNGE_BENCH_REPEAT", "3"))
if not os.path.abspath(PlungeRough.__file__).startswith(ROOT):
    sys.exit("the addon was loaded from %s, not this tree: run with a fresh XDG_DATA_HOME" % PlungeRough.__file__)
part = tray()
floor = tray_floor(part)
doc = FreeCAD.newDocument("BenchTray")
job = make_job(doc, part)
op, tcs = add_plunge_rough(job, floor, diameters=(12, 8, 5), MaxFloorStock=1.0, RadialAllowance=0.5,
                           FloorAllowance=0.3)

program = bundle_program(ROOT)
print("| planner | recompute | planning | plunges | floor-stock plunges | floor stock left (max / mean) |")
print("|---|---|---|---|---|---|")
for name, through_bundle in PLANNERS:
    whole, planning, plan = recompute_timed(doc, op, program if through_bundle else None, REPEAT)
    s = plan["stats"]
    print("| %s | %.1f s | %.1f s | %d | %d | %.2f / %.2f mm |" % (
        name, statistics.median(whole), statistics.median(planning), s["plunge_count"], s["floor_stock_plunges"],
        s["max_floor_stock_left"], s["mean_floor_stock"]))
    print("  planned by", planner.planner().name, file=sys.stderr)
