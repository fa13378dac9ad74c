"""Run by freecadcmd: the FreeCAD demo's plan input (resources/examples, the
B-spline floor of freeform_part) with its floor as the addon meshes it for a
planner without OpenCASCADE (freecad_plugin/floor_mesh.py), written as JSON to
the path in PLUNGE_DEMO_MESH_INPUT. A golden input of the portable programs
(test_portable.py)."""
import json
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path[:0] = [ROOT, os.path.join(ROOT, "resources", "examples")]

import FreeCAD  # noqa: E402

from example_part import add_plunge_rough, floor_face_name, freeform_part, make_job  # noqa: E402
from freecad_plugin import operation_input, planner  # noqa: E402

doc = FreeCAD.newDocument("DemoMesh")
job = make_job(doc, freeform_part())
op, tcs = add_plunge_rough(job, floor_face_name(job.Model.Group[0].Shape, True))
faces = operation_input.selected_faces(op, tcs)
data = operation_input.build_input(op, tcs, faces, FreeCAD.getUserAppDataDir(), floors=("z", "expression", "mesh"))
assert "mesh" in data["floor"], data["floor"]
with open(os.environ["PLUNGE_DEMO_MESH_INPUT"], "w") as f:
    json.dump(data, f)
print("DEMO_MESH_INPUT=%d triangles" % len(data["floor"]["mesh"]["triangles"]))
