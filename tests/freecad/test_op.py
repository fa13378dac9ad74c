"""The Plunge Rough operation headless: paths checked against the part's own geometry."""
import json
import math
import os

import FreeCAD
import Part
import pytest

import parts
from conftest import build_op
from gcode import job_program, path_blocks, replay
from machine_check import assert_machinable, check_program
from freecad_plugin import companions, compat, operation_input, PlungeRough


def plunges_of(job):
    """Every plunge of the job's operations: (tool controller, x, y, z), in order."""
    out = []
    for op in job.Operations.Group:
        tc = op.ToolController
        plunges, low = replay(path_blocks(op), op.SafeHeight.Value if hasattr(op, "SafeHeight") else -1e9)
        out += [(tc, x, y, z) for _, x, y, z in plunges]
    return out


def assert_no_gouge(part, floor_names, plunges, top, radial, floor, every=1):
    """No gouge, from the part's own geometry: the plunger's cylinder from its stop
    height minus the floor allowance up to the top holds no material, and its axis
    keeps radius + radial allowance from every face but the floor."""
    walls = [f for i, f in enumerate(part.Faces) if "Face%d" % (i + 1) not in floor_names]
    for tc, x, y, z in plunges[::every]:
        r = float(tc.Tool.Diameter) / 2
        bottom = z - floor + 1e-4
        cyl = Part.makeCylinder(r - 1e-4, top - bottom, FreeCAD.Vector(x, y, bottom))
        assert part.common(cyl).Volume < 1e-6, ("floor or wall", tc.Label, x, y, z)
        axis = Part.makeLine(FreeCAD.Vector(x, y, z + 0.5), FreeCAD.Vector(x, y, top))
        clearance = min(axis.distToShape(w)[0] for w in walls)
        assert clearance >= r + radial - 1e-4, ("wall", tc.Label, x, y, clearance)


def assert_touches(part, plunges, floor, every=1):
    """Tight: 0.01 mm lower, the plunger's disk meets the floor."""
    for tc, x, y, z in plunges[::every]:
        r = float(tc.Tool.Diameter) / 2 - 1e-3
        cyl = Part.makeCylinder(r, 0.5, FreeCAD.Vector(x, y, z - floor - 0.01))
        assert part.common(cyl).Volume > 0, (tc.Label, x, y, z)


def floor_max(face, x, y, r, rings=6, spokes=72):
    """Highest point of the floor face under the disk, by sectioning vertical lines."""
    best = -math.inf
    for i in range(rings + 1):
        rr = r * i / rings
        for k in range(spokes if i else 1):
            t = 2 * math.pi * k / spokes
            px, py = x + rr * math.cos(t), y + rr * math.sin(t)
            line = Part.makeLine(FreeCAD.Vector(px, py, -100), FreeCAD.Vector(px, py, 100))
            for v in face.section(line).Vertexes:
                best = max(best, v.Point.z)
    return best


@pytest.mark.bundle
def test_flat_pocket_with_islands(doc):
    job, op, tcs = build_op(doc, parts.islands_part(), sculptured=False)
    ops = job.Operations.Group
    # One operation per plunger, largest first, each with its own tool controller.
    assert [float(o.ToolController.Tool.Diameter) for o in ops] == [20, 12, 6]
    assert ops[0] == op and all(getattr(o, "PlanOperation", op) == op for o in ops)
    plan = PlungeRough.plan_of(op)
    plunges = plunges_of(job)
    assert len(plunges) == plan["stats"]["plunge_count"] > 0
    # The plan's tool for every plunge is the tool that makes it.
    numbers = [int(tc.ToolNumber) for tc, *_ in plunges]
    assert numbers == [p["tool_id"] for p in plan["plunges"]]
    for o in ops:
        assert o.Path.Commands[-1].Parameters.get("Z") == op.ClearanceHeight.Value
    # The paths run against a simulated stock: rapids never through it (they go
    # down close to it, stock-aware), lead-outs and plunges never gouge.
    data = json.loads(op.PlanData)["input"]
    assert_machinable(check_program(data, data["tools"], job_program(job)))
    assert any("lead_out" in p for p in plan["plunges"])
    part = job.Model.Group[0].Shape
    assert all(abs(z - (10 + 0.3)) < 1e-9 for *_, z in plunges)  # floor 10 mm + allowance
    assert_no_gouge(part, op.Base[0][1], plunges, op.StartDepth.Value, 0.5, 0.3)
    assert_touches(part, plunges, 0.3, every=5)
    # The default 1 mm wall band: the core cut whole, no thicker wall stock, said in the summary.
    assert plan["stats"]["core_coverage"] > 0.9999 and plan["stats"]["max_wall_stock_left"] <= 1.0 + 1e-9
    assert "coverage" in op.Summary and "min" in op.Summary and "stock left: walls up to" in op.Summary


@pytest.mark.bundle
def test_sculptured_floor_and_freeform_walls(doc):
    job, op, tcs = build_op(doc, parts.freeform_part(True), sculptured=True)
    plunges = plunges_of(job)
    plan = PlungeRough.plan_of(op)
    assert len(plunges) == plan["stats"]["plunge_count"]
    zs = [z for *_, z in plunges]
    assert max(zs) - min(zs) > 2  # depths follow the floor
    part = job.Model.Group[0].Shape
    assert_no_gouge(part, op.Base[0][1], plunges, op.StartDepth.Value, 0.5, 0.3, every=3)
    # Tight: within 0.01 mm of the highest floor point under each disk (sampled
    # sections of the floor face can only see lower points than the true maximum).
    face = part.getElement(op.Base[0][1][0])
    for tc, x, y, z in plunges[::15]:
        highest = floor_max(face, x, y, float(tc.Tool.Diameter) / 2)
        assert z - 0.3 - highest < 0.01, (tc.Label, x, y, z, highest)
        assert z - 0.3 - highest > -1e-6, (tc.Label, x, y, z, highest)
    # The demo part with the demo's plungers: no floor stock above the default 1 mm.
    assert plan["stats"]["floor_stock_plunges"] > 0 and plan["stats"]["max_floor_stock_left"] <= 1.0
    assert not any("stock stay above the floor" in w for w in plan.get("warnings", []))
    assert "floor up to 0." in op.Summary


def test_build_input_is_the_planner_input_of_the_properties(doc, tmp_path):
    import jsonschema
    job, op, tcs = build_op(doc, parts.islands_part(), sculptured=False)
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    with open(os.path.join(root, "docs", "plan-input.schema.json")) as f:
        schema = jsonschema.Draft202012Validator(json.load(f))
    plungers = companions.tool_controllers(op)
    faces = operation_input.selected_faces(op, plungers)
    before = (op.PlanData, op.Summary, [c.Name for c in op.Path.Commands])
    data = operation_input.build_input(op, plungers, faces, str(tmp_path))
    assert data == json.loads(op.PlanData)["input"]  # what the operation planned with
    assert (op.PlanData, op.Summary, [c.Name for c in op.Path.Commands]) == before  # changed nothing
    schema.validate(data)
    # New operations choose their plungers (AutoSelectTools): all of them are the library.
    assert op.AutoSelectTools and data["tools"] == "auto"
    assert [t["diameter"] for t in data["tool_library"]] == [20, 12, 6]
    assert [t["id"] for t in data["tool_library"]] == [int(tc.ToolNumber) for tc in plungers]
    assert (data["top_z"], data["safe_z"], data["final_depth"]) == (
        op.StartDepth.Value, op.SafeHeight.Value, op.FinalDepth.Value)
    assert data["floor"] == {"z": 10.0} and data["allowance"]["floor"] == 0.3
    # The chords of the round island lie off it by at most the chord tolerance: added.
    assert 0.5 < data["allowance"]["radial"] <= 0.5 + op.ChordTolerance.Value + 1e-5
    xs, ys = [p[0] for p in data["boundary"]], [p[1] for p in data["boundary"]]
    assert (min(xs), max(xs), min(ys), max(ys)) == pytest.approx((10, 150, 10, 90))
    assert len(data["islands"]) == 2
    # The options as the planner's keys.
    assert data["growth_pattern"] == "auto" and data["time_model"]["tool_change_seconds"] == 20.0
    op.UseCannedCycle = True
    op.Strategy = "Grid (square)"
    op.AutoSelectTools = True
    op.GrowthPattern = "Offsets"
    op.ToolChangeTime = 45.0
    data = operation_input.build_input(op, plungers, faces, str(tmp_path))
    schema.validate(data)
    assert data["growth_pattern"] == "offsets" and data["time_model"]["tool_change_seconds"] == 45.0
    assert data["lead_out"] == 0.0 and data["stock_aware_heights"] is False
    assert data["strategy"] == "grid" and data["grid"] == {"pattern": "square"}
    assert data["tools"] == "auto" and [t["diameter"] for t in data["tool_library"]] == [20, 12, 6]
    op.SafeHeight = op.ClearanceHeight.Value + 1
    with pytest.raises(ValueError, match="safe height"):
        operation_input.build_input(op, plungers, faces, str(tmp_path))


def test_no_plunge_below_the_final_depth(doc):
    job, op, tcs = build_op(doc, parts.freeform_part(True), sculptured=True)
    deepest = min(p["z"] for p in PlungeRough.plan_of(op)["plunges"])
    op.setExpression("FinalDepth", None)
    op.FinalDepth = deepest + 2  # above the floor's low part: rough down to there only
    doc.recompute()
    plunges = plunges_of(job)
    assert json.loads(op.PlanData)["input"]["final_depth"] == op.FinalDepth.Value == deepest + 2
    zs = [z for *_, z in plunges]
    assert min(zs) == pytest.approx(deepest + 2 + 0.3)
    assert max(zs) > deepest + 2 + 0.3 + 1  # where the floor is higher, the floor decides


def test_canned_cycles_with_pecking(doc):
    job, op, _ = build_op(doc, parts.islands_part(), sculptured=False, canned=True, peck=4.0)
    names = [c.Name for c in op.Path.Commands]
    assert "G98" in names and "G80" in names and "G83" in names and "G1" not in names
    cycle = next(c for c in op.Path.Commands if c.Name == "G83")
    assert cycle.Parameters["Q"] == 4.0 and cycle.Parameters["R"] == op.SafeHeight.Value
    assert cycle.Parameters["F"] == op.ToolController.VertFeed.Value  # plunging at the vertical feed


def test_unusable_selections_give_a_message_and_no_path(doc):
    job, op, _ = build_op(doc, parts.islands_part(), sculptured=False)
    clone = job.Model.Group[0]
    vertical = next("Face%d" % (i + 1) for i, f in enumerate(clone.Shape.Faces)
                    if isinstance(f.Surface, Part.Plane) and abs(f.Surface.Axis.z) < 1e-9)
    for sub, message in [(vertical, "vertical"), ("Edge1", "not a face")]:
        op.Base = [(clone, [sub])]
        doc.recompute()
        assert message in op.Summary
        assert not any(c.Name in ("G1", "G81", "G83") for c in op.Path.Commands)
        assert op.PlanData == ""


def test_bad_settings_give_a_message(doc):
    job, op, tcs = build_op(doc, parts.islands_part(), sculptured=False)
    op.RadialAllowance = 45  # nothing fits any more
    doc.recompute()
    assert "no tool fits" in op.Summary
    assert not any(c.Name == "G1" for c in op.Path.Commands)


def test_tool_controllers_change(doc):
    job, op, tcs = build_op(doc, parts.islands_part(), sculptured=False)
    op.ToolControllers = tcs[:2]
    doc.recompute()
    assert [float(o.ToolController.Tool.Diameter) for o in job.Operations.Group] == [20, 12]
    op.ToolControllers = [tcs[2], tcs[1]]  # any order; the largest becomes the op's own
    doc.recompute()
    assert float(op.ToolController.Tool.Diameter) == 12
    assert [float(o.ToolController.Tool.Diameter) for o in job.Operations.Group] == [12, 6]


def test_saved_and_restored(doc, tmp_path):
    job, op, tcs = build_op(doc, parts.islands_part(), sculptured=False)
    count = PlungeRough.plan_of(op)["stats"]["plunge_count"]
    name = op.Name
    # A file from before the growth pattern, tool change time and rest
    # plunging: they come back with their defaults, and rest plunging off
    # (solid stock from the start depth, the plan as it was planned).
    for prop in ("GrowthPattern", "ToolChangeTime", "RestFrom", "RestResolution", "RestSources"):
        op.removeProperty(prop)
    path = str(tmp_path / "plunge.FCStd")
    doc.saveAs(path)
    FreeCAD.closeDocument(doc.Name)
    again = FreeCAD.openDocument(path)
    try:
        op2 = again.getObject(name)
        assert isinstance(op2.Proxy, PlungeRough.ObjectPlungeRough)
        assert op2.RadialAllowance.Value == 0.5 and len(op2.ToolControllers) == 3
        assert op2.GrowthPattern == "Auto" and op2.ToolChangeTime == 20.0
        assert op2.RestFrom == "None" and op2.RestResolution.Value == 0.0
        op2.touch()
        again.recompute()
        assert PlungeRough.plan_of(op2)["stats"]["plunge_count"] == count
        assert [o.Label for o in again.getObject("Job").Operations.Group][1:] == \
            ["PlungeRough T3 12 mm", "PlungeRough T4 6 mm"]
    finally:
        FreeCAD.closeDocument(again.Name)


def test_auto_select_tools(doc, tmp_path):
    """The planner picks from the ticked plungers; every tool change the post writes
    is followed by plunges (a 90 mm plunger fits nowhere: it must stay idle even
    though it is the operation's largest)."""
    job = parts.make_job(doc, parts.islands_part())
    op, tcs = parts.add_plunge_rough(job, parts.floor_face_name(job.Model.Group[0].Shape, False),
                                     (90, 20, 16, 12, 8, 6), RadialAllowance=0.5, FloorAllowance=0.3,
                                     AutoSelectTools=True)
    plan = PlungeRough.plan_of(op)
    assert "Touched" not in op.State  # switching its own tool controller left nothing to recompute
    selection = plan["tool_selection"]
    chosen = selection["chosen"]
    assert set(chosen) <= {20, 16, 12, 8, 6} and chosen[-1] == 6
    assert "chosen" in op.Summary
    assert float(op.ToolController.Tool.Diameter) == chosen[0]  # the op cuts with the largest chosen
    plunges = plunges_of(job)
    assert len(plunges) == plan["stats"]["plunge_count"]
    assert sorted(float(tc.Tool.Diameter) for tc, *_ in plunges) == sorted(p["diameter"] for p in plan["plunges"])
    assert {float(tc.Tool.Diameter) for tc, *_ in plunges} == set(chosen)
    comps = companions.companions(op)
    assert [c for c in comps if not c.Active], "the library holds sizes the selection does not take"
    assert_no_gouge(job.Model.Group[0].Shape, op.Base[0][1], plunges, op.StartDepth.Value, 0.5, 0.3, every=2)
    text = compat.post_job(job, "linuxcnc", "--no-header --no-show-editor")
    changed = [int(w[1:]) for line in text.splitlines() if line.startswith("M6") for w in line.split() if w[0] == "T"]
    number = {float(tc.Tool.Diameter): int(tc.ToolNumber) for tc in tcs}
    assert changed == [number[d] for d in chosen]  # one change per chosen plunger, largest first
    # Recomputing again changes nothing; off again, every plunger works with the largest first.
    doc.recompute()
    assert PlungeRough.plan_of(op)["plunges"] == plan["plunges"] and "Invalid" not in op.State
    op.AutoSelectTools = False
    doc.recompute()
    assert all(c.Active for c in comps)
    assert float(op.ToolController.Tool.Diameter) == 90
    assert "tool_selection" not in PlungeRough.plan_of(op)


def test_grid_strategy(doc):
    """The grid baseline through the op: gouge-free, and it leaves more than packing."""
    job, op, tcs = build_op(doc, parts.islands_part(), sculptured=False)
    packed = PlungeRough.plan_of(op)["stats"]["coverage"]
    op.Strategy = "Grid (honeycomb)"
    doc.recompute()
    plan = PlungeRough.plan_of(op)
    plunges = plunges_of(job)
    assert len(plunges) == plan["stats"]["plunge_count"] > 0
    assert_no_gouge(job.Model.Group[0].Shape, op.Base[0][1], plunges, op.StartDepth.Value, 0.5, 0.3, every=2)
    assert plan["stats"]["coverage"] < packed
    assert op.getEnumerationsOfProperty("Strategy") == ["Packing", "Grid (honeycomb)", "Grid (square)"]
