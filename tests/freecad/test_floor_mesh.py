"""A floor's faces as the addon meshes them for a planner without OpenCASCADE
(freecad_plugin/floor_mesh.py): within its said deviation of the faces,
measured here by OpenCASCADE's own projection; and the stops planned on it
against the stops planned on the faces themselves (BREP): never below them,
at most 0.01 mm above, with flat, ball and bull plungers, on the demo's
B-spline floor and on a filleted pocket."""
import json
import random

import FreeCAD
import Part
import pytest

import parts
from conftest import build_op
from freecad_plugin import floor_mesh, geometry, operation_input, planner
from test_pockets import faces_at, filleted_pocket, job_with_op

V = FreeCAD.Vector
TOOLS = {"flat": {}, "ball": {"shape": "ball"}, "bull": {"shape": "bull", "corner_radius": 2.0}}


def sculptured_op(doc):
    return build_op(doc, parts.freeform_part(), sculptured=True, diameters=(20, 12))


def filleted_op(doc):
    """The filleted pocket of test_pockets (a 3 mm fillet between floor and
    walls, added to the floor), 12/8/5 mm plungers."""
    obj = filleted_pocket(doc)
    return job_with_op(doc, obj, faces_at(obj.Shape, obj.Shape.BoundBox.ZMin + 10))


@pytest.fixture(scope="module", params=[sculptured_op, filleted_op], ids=["sculptured", "filleted"])
def pocket(request, tmp_path_factory):
    """Each part once: its floor faces, and the operation's planner input with
    the floor as BREP faces and as the addon's mesh."""
    doc = FreeCAD.newDocument("FloorMesh_" + request.param.__name__)
    job, op, tcs = request.param(doc)
    selected = operation_input.selected_faces(op, tcs)
    faces = [f for _, f in geometry.pocket(selected, op.ChordTolerance.Value, op.IncludeFillets, 2.0,
                                           operation_input.model_of(op)).faces]
    folder = str(tmp_path_factory.mktemp("floor"))
    brep = operation_input.build_input(op, tcs, selected, folder, floors=("z", "brep"))
    mesh = operation_input.build_input(op, tcs, selected, folder, floors=("z", "expression", "mesh"))
    assert "brep" in brep["floor"] and "mesh" in mesh["floor"]
    yield [f.copy() for f in faces], brep, mesh
    FreeCAD.closeDocument(doc.Name)


def test_the_mesh_lies_within_its_deviation_of_the_faces(pocket):
    faces, _, data = pocket
    mesh = data["floor"]["mesh"]
    deviation = mesh["deviation"]
    assert len(deviation) == len(mesh["triangles"])
    assert 0 < max(deviation) <= floor_mesh.DEVIATION * floor_mesh.MARGIN
    compound = Part.makeCompound(faces)
    rng = random.Random(5)
    worst = 0.0  # the distance to the faces over the triangle's own deviation
    for k in rng.sample(range(len(mesh["triangles"])), min(1500, len(mesh["triangles"]))):
        a, b, c = (V(*mesh["vertices"][i]) for i in mesh["triangles"][k])
        u, v = rng.random(), rng.random()
        if u + v > 1:
            u, v = 1 - u, 1 - v
        p = a + (b - a) * u + (c - a) * v
        worst = max(worst, compound.distToShape(Part.Vertex(p))[0] - deviation[k])
    assert worst <= 1e-7, worst


@pytest.mark.parametrize("kind", sorted(TOOLS))
def test_stops_on_the_mesh_are_the_stops_on_the_faces_to_a_hundredth(pocket, kind):
    _, brep, mesh = pocket
    module = planner.planner()
    assert isinstance(module, planner.Module)  # both floor kinds in one build
    plans = []
    for data in (brep, mesh):
        data = json.loads(json.dumps(data))
        for tool in data["tools"] if data["tools"] != "auto" else data["tool_library"]:
            tool.update(TOOLS[kind])
        # Plunges on a grid, none added for floor stock: the same places on both floors.
        data.update(strategy="grid", grid={"pattern": "square"}, max_floor_stock=0, stock_aware_heights=False)
        plans.append({(round(p["x"], 6), round(p["y"], 6), p["tool_id"], p["level"]): p["z"]
                      for p in module.plan(data)["plunges"]})
    on_faces, on_mesh = plans
    assert set(on_faces) == set(on_mesh) and len(on_faces) > 30
    below = max(on_faces[k] - on_mesh[k] for k in on_faces)
    above = max(on_mesh[k] - on_faces[k] for k in on_faces)
    # The faces' own stops are a search, tight to about 0.001 mm.
    assert below <= 0.001, below
    assert above <= 0.01, above
