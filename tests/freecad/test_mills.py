"""A Job with a real plunge mill, built as a user does: an indexable plunge cutter
that does not cut at its centre (its bit given a CoreDiameter and a
MaxEngagement with the property editor's "Add property"), a centre-cutting
plunger for its start holes, lead-out on. The plan, the simulation with each
tool's own solid and the posted program, run through the G-code checker."""
import json
import math
import os

import FreeCAD
import pytest

import parts
from freecad_plugin import PlungeRough, compat, plunge_mill, tools
from freecad_plugin.compat import post_job
from gcode import parse_gcode, replay
from machine_check import assert_machinable, check_program
from test_sim import height_map, simulate


def plunge_cutter_job(doc):
    job = parts.make_job(doc, parts.islands_part())
    tcs = [parts.add_tool_controller(job, d, i + 2) for i, d in enumerate((20, 12, 6))]
    bit = tcs[0].Tool
    # What a user types into the bit's property editor ("Add property", group Attributes).
    bit.addProperty("App::PropertyLength", "CoreDiameter", "Attributes")
    bit.CoreDiameter = 6.0
    bit.addProperty("App::PropertyLength", "MaxEngagement", "Attributes")
    bit.MaxEngagement = 8.0
    op = PlungeRough.Create("PlungeRough", parentJob=job)
    op.Base = [(job.Model.Group[0], [parts.floor_face_name(job.Model.Group[0].Shape, False)])]
    op.RadialAllowance = 0.5
    op.FloorAllowance = 0.3
    doc.recompute()
    return job, op, tcs


@pytest.mark.bundle
def test_plunge_cutter_job_plans_simulates_and_posts_a_checked_program(doc):
    job, op, tcs = plunge_cutter_job(doc)
    plan = PlungeRough.plan_of(op)
    assert plan is not None, op.Summary
    stats = plan["stats"]
    assert stats["start_holes"] >= 1 and "start holes" in op.Summary
    # Start holes by the 6 mm plunger before the plunge cutter, the other plungers after it.
    ops = job.Operations.Group
    assert [o.Label for o in ops][0].endswith("start holes")
    assert ops[1] == op and ops[0].ToolController == tcs[2]
    holes = [p for p in plan["plunges"] if p["start_hole"]]
    assert holes and all(p["tool_id"] == int(tcs[2].ToolNumber) for p in holes)
    spec = [tools.spec(tc) for tc in tcs]
    assert spec[0]["center_cutting"] is False and spec[0]["core_diameter"] == 6.0
    assert spec[0]["max_engagement"] == 8.0 and spec[0]["flute_length"] == 50.0

    # The posted program against a simulated stock: engagement, core, lead-outs, rapids.
    text = post_job(job, "linuxcnc", "--no-header --no-show-editor")
    data = json.loads(op.PlanData)["input"]
    report = check_program(data, data["tools"], text)
    assert_machinable(report)
    assert report["plunges"] == stats["plunge_count"]
    assert report["lead_outs"] > 0
    assert report["max_engagement"][int(tcs[0].ToolNumber)] <= 8.0 + 1.5 * 0.75
    plunges, _ = replay(parse_gcode(text), op.SafeHeight.Value)
    assert len(plunges) == stats["plunge_count"]

    # FreeCAD's simulator, each operation with its tool controller's own solid:
    # it removes what the plan removes.
    stock = job.Stock.Shape
    meshes = simulate(job, 0.5, op.ClearanceHeight.Value)
    box = stock.BoundBox
    xs = [box.XMin + 0.5 + 2 * i for i in range(int(box.XLength / 2) - 1)]
    ys = [box.YMin + 0.5 + 2 * j for j in range(int(box.YLength / 2) - 1)]
    simulated = height_map(meshes, xs, ys, box.ZMax)
    compared = wrong = 0
    for (x, y), z in simulated.items():
        edges = [abs(math.hypot(x - p["x"], y - p["y"]) - p["diameter"] / 2) for p in plan["plunges"]]
        if min(edges) < 1.0:
            continue  # a voxel's width (plus a lead-out) from a disk's edge
        inside = [p["z"] for p in plan["plunges"] if math.hypot(x - p["x"], y - p["y"]) < p["diameter"] / 2]
        expected = min(inside) if inside else box.ZMax
        compared += 1
        wrong += z is None or abs(z - expected) > 0.5
    assert compared > 1000
    assert wrong <= 0.005 * compared, (wrong, compared)


def test_a_plunge_cutter_without_a_start_hole_tool_is_reported(doc):
    job = parts.make_job(doc, parts.islands_part())
    tc = parts.add_tool_controller(job, 20, 2)
    tc.Tool.addProperty("App::PropertyLength", "CoreDiameter", "Attributes")
    tc.Tool.CoreDiameter = 8.0
    op = PlungeRough.Create("PlungeRough", parentJob=job)
    op.Base = [(job.Model.Group[0], [parts.floor_face_name(job.Model.Group[0].Shape, False)])]
    doc.recompute()
    assert PlungeRough.plan_of(op) is None
    assert "does not cut at its centre" in op.Summary and "centre-cutting tool" in op.Summary


def library_plunge_mill(doc, root, diameter):
    """The plunge mill of the given diameter as a user picks it from the tool
    library that plunge_mill.install() made (what resources/install_addon.sh
    runs): up to 1.0 the library file lists bit files beside it, each finding
    its shape in the Shape folder; in 1.1 the library is an asset of the user's
    CAM library, its bits and their shape too."""
    plunge_mill.install(root)
    name = plunge_mill.bit_name({"Diameter": diameter})
    assets = compat.tool_library()
    if assets is None:
        with open(os.path.join(root, "Tools", "Library", plunge_mill.LIBRARY + ".fctl")) as f:
            library = json.load(f)
        paths = [os.path.join(root, "Tools", "Bit", t["path"]) for t in library["tools"]]
        path = next(p for p in paths if json.load(open(p))["name"] == name)
        return compat.tool_bit_from_file(path, doc)
    library = assets.get("toolbitlibrary://" + plunge_mill.LIBRARY)
    bit = next(b for b in library.get_bits() if b.label == name)
    return bit.attach_to_doc(doc)


def test_a_plunge_mill_from_the_tool_library_plans_with_its_core_and_limit(doc, tmp_path):
    job = parts.make_job(doc, parts.islands_part())
    bit = library_plunge_mill(doc, str(tmp_path), 25)
    assert compat.bit_shape(bit) == plunge_mill.SHAPE
    # The bit's solid is the shape's, to scale: diameter, and the core recess
    # (no material on the axis just above the tip).
    box = bit.Shape.BoundBox
    assert box.XLength == pytest.approx(25, abs=1e-6) and box.ZMin == pytest.approx(0, abs=1e-6)
    assert not bit.Shape.isInside(FreeCAD.Vector(0, 0, 1), 1e-6, True)
    assert bit.Shape.isInside(FreeCAD.Vector(10, 0, 1), 1e-6, True)
    mill = compat.PathToolController.Create("TC: 25 mm plunge mill", tool=bit, toolNumber=5)
    mill.VertFeed = "150 mm/min"
    job.Proxy.addToolController(mill)
    small = parts.add_tool_controller(job, 16, 6)  # centre-cutting, wider than the core: the start holes
    assert tools.is_plunger(mill)
    op = PlungeRough.Create("PlungeRough", parentJob=job)
    op.Base = [(job.Model.Group[0], [parts.floor_face_name(job.Model.Group[0].Shape, False)])]
    op.ToolControllers = [mill, small]
    op.RadialAllowance = 0.5
    doc.recompute()
    plan = PlungeRough.plan_of(op)
    assert plan is not None, op.Summary
    spec = tools.spec(mill)
    assert spec["center_cutting"] is False and spec["core_diameter"] == 13.0 and spec["max_engagement"] == 6.0
    assert spec["flute_length"] == 80.0
    mine = [p for p in plan["plunges"] if p["tool_id"] == 5]
    assert mine and plan["stats"]["start_holes"] >= 1
    text = post_job(job, "linuxcnc", "--no-header --no-show-editor")
    data = json.loads(op.PlanData)["input"]
    report = check_program(data, data["tools"], text)
    assert_machinable(report)
    assert report["max_engagement"][5] <= 6.0 + 1.5 * 0.75
