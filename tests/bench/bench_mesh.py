"""The FreeCAD demo's sculptured floor planned two ways, as users get them:
through the README's install (the module, the floor as BREP faces) and
through the Linux bundle's program (no OpenCASCADE: the floor as the addon's
mesh). Prints the whole recompute, the mesh's making and the planner's own
time each way (median of --repeat), and the plans' plunges and estimated time.

    sh resources/bundle.sh linux
    freecadcmd tests/bench/bench_mesh.py        # after the build (build/)

PLUNGE_BENCH_REPEAT (default 5) sets the repeats."""
import json
import os
import statistics
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path[:0] = [ROOT, os.path.join(ROOT, "build", "cpp"), os.path.join(ROOT, "resources", "examples"),
                os.path.dirname(os.path.abspath(__file__))]

import FreeCAD  # noqa: E402

from both_planners import PLANNERS, bundle_program, program_timed, recompute_timed  # noqa: E402
from example_part import add_plunge_rough, floor_face_name, freeform_part, make_job  # noqa: E402
from freecad_plugin import floor_mesh, planner  # noqa: E402

REPEAT = int(os.environ.get("PLUNGE_BENCH_REPEAT", "5"))
program = bundle_program(ROOT)

doc = FreeCAD.newDocument("BenchMesh")
job = make_job(doc, freeform_part())
op, tcs = add_plunge_rough(job, floor_face_name(job.Model.Group[0].Shape, True))

timings = {}
real_mesh = floor_mesh.floor_mesh


def timed_mesh(faces, *args, **kwargs):
    start = time.perf_counter()
    out = real_mesh(faces, *args, **kwargs)
    timings.setdefault("mesh", []).append(time.perf_counter() - start)
    return out


floor_mesh.floor_mesh = timed_mesh
rows = []
for name, through_bundle in PLANNERS:
    timings.clear()
    whole, planning, plan = recompute_timed(doc, op, program if through_bundle else None, REPEAT)
    floor = json.loads(op.PlanData)["input"]["floor"]
    rows.append((name, statistics.median(whole), statistics.median(timings["mesh"]) if "mesh" in timings else None,
                 statistics.median(planning), plan["stats"]["plunge_count"], plan["stats"]["estimated_minutes"],
                 len(floor["mesh"]["triangles"]) if "mesh" in floor else None, planner.planner().name))
print("| planner | recompute | mesh made in | planning | plunges | est. time | triangles |")
print("|---|---|---|---|---|---|---|")
for name, whole, mesh, planning, count, minutes, triangles, _ in rows:
    print("| %s | %.2f s | %s | %.2f s | %d | %.1f min | %s |" % (
        name, whole, "%.2f s" % mesh if mesh is not None else "-", planning, count, minutes,
        triangles if triangles is not None else "-"))
print("through the mesh / through the BREP: recompute %.2f x, planning %.2f x" % (rows[1][1] / rows[0][1],
                                                                                    rows[1][3] / rows[0][3]))
# The recompute against the program's own plan of the same input: the native
# program (the README's install plans through it) on the BREP floor.
native = os.path.join(ROOT, "build", "cpp", "plunge-rough")
os.environ[planner.ENVIRONMENT] = native
whole, _, _ = recompute_timed(doc, op, native, REPEAT)
alone = program_timed(native, json.loads(op.PlanData)["input"], REPEAT, os.path.join(ROOT, "build"))
print("native program, BREP floor: recompute %.2f s, the program's plan of the same input %.2f s: %.2f x" % (
    statistics.median(whole), statistics.median(alone), statistics.median(whole) / statistics.median(alone)))
for row in rows:
    print("planned by", row[-1])
