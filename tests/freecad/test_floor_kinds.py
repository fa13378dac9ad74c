"""The same plan through the mesh as through the faces: a planner without
OpenCASCADE (the bundles' program, on every FreeCAD) gets the floor as the
addon's mesh (freecad_plugin/floor_mesh.py), the README's install gets its
BREP faces. On every kind of floor the suite and the demos plan (B-spline,
filleted, several faces, the tray), both plans choose the same plungers, take
an estimated time within 2 % of each other and plunge within 5 %; and each
says which floor it planned on."""
import json

import FreeCAD
import pytest

import parts
from conftest import build_op
from freecad_plugin import PlungeRough, operation_input, planner
from test_pockets import faces_at, filleted_pocket, job_with_op


def sculptured(doc):
    """The demo: the B-spline floor, 20/12/6 mm plungers, the tool choice on."""
    return build_op(doc, parts.freeform_part(), sculptured=True)


def filleted(doc):
    """A pocket whose floor is a plane and the fillets around it (several
    faces), 12/8/5 mm plungers."""
    obj = filleted_pocket(doc)
    return job_with_op(doc, obj, faces_at(obj.Shape, obj.Shape.BoundBox.ZMin + 10))


def tray(doc):
    """The tray: its floor and its R6 fillets, 12/8/5 mm plungers, 1 mm floor stock."""
    job = parts.make_job(doc, parts.tray())
    op, tcs = parts.add_plunge_rough(job, parts.tray_floor(job.Model.Group[0].Shape), diameters=(12, 8, 5),
                                     MaxFloorStock=1.0, RadialAllowance=0.5, FloorAllowance=0.3)
    return job, op, tcs


@pytest.fixture(scope="module", params=[sculptured, filleted, tray])
def plans(request, tmp_path_factory):
    """The operation's input with the floor as faces and as the mesh, each
    planned by the module (both floor kinds in one build)."""
    doc = FreeCAD.newDocument("FloorKinds_" + request.param.__name__)
    job, op, tcs = request.param(doc)
    assert PlungeRough.plan_of(op) is not None, op.Summary
    selected = operation_input.selected_faces(op, tcs)
    folder = str(tmp_path_factory.mktemp("kinds"))
    module = planner.planner()
    assert isinstance(module, planner.Module)
    out = {}
    for kind, floors in (("brep", ("z", "brep")), ("mesh", ("z", "expression", "mesh"))):
        data = operation_input.build_input(op, tcs, selected, folder, floors=floors)
        assert kind in data["floor"], data["floor"].keys()
        out[kind] = module.plan(json.loads(json.dumps(data)))
    yield out
    FreeCAD.closeDocument(doc.Name)


def test_the_mesh_plans_as_the_faces_do(plans):
    faces, mesh = plans["brep"], plans["mesh"]
    used = [sorted({p["tool_id"] for p in plan["plunges"]}) for plan in (faces, mesh)]
    assert used[0] == used[1], used
    f, m = faces["stats"], mesh["stats"]
    assert m["estimated_minutes"] == pytest.approx(f["estimated_minutes"], rel=0.02), (f, m)
    assert m["plunge_count"] == pytest.approx(f["plunge_count"], rel=0.05), (f, m)
    assert m["floor_stock_plunges"] == pytest.approx(f["floor_stock_plunges"], rel=0.05, abs=3), (f, m)


def test_each_plan_says_its_floor_kind(plans):
    for kind, plan in plans.items():
        assert plan["stats"]["floor_kind"] == kind
