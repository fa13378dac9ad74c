"""Holders kept clear in a deep pocket, end to end: a part modelled with Part
booleans, a Job with a plunger from its .fctb, the operation's stick-out and
holder, the Job's posted G-code replayed on a height field of the stock with
the holder (gcode_replay.py, which shares no code with the planner)."""
import FreeCAD
import Part
import pytest

from freecad_plugin import PlungeRough, compat
import parts
from gcode_replay import Stock, holder_hits, read_program, tools_of

V = FreeCAD.Vector


def deep_part():
    """A 190 x 130 x 80 block with a 150 x 90 pocket 70 mm deep around a 20 x 20 island."""
    block = Part.makeBox(190, 130, 80)
    pocket = Part.makeBox(150, 90, 80, V(20, 20, 10)).cut(Part.makeBox(20, 20, 80, V(85, 55, 0)))
    return block.cut(pocket).removeSplitter()


@pytest.mark.bundle
def test_a_deep_pocket_keeps_the_holder_clear_at_every_posted_move(doc):
    job = parts.make_job(doc, deep_part())
    face = parts.floor_face_name(job.Model.Group[0].Shape, False)
    # The plunger's bit has 50 mm flutes; held 60 mm out in a 40 mm holder.
    op, tcs = parts.add_plunge_rough(job, face, (20,), StickOut=60.0, HolderDiameter=40.0, HolderClearance=1.0,
                                     RadialAllowance=0.3, FloorAllowance=0.2)
    plan = PlungeRough.plan_of(op)
    assert plan is not None, op.Summary
    limited = [p for p in plan["plunges"] if p.get("holder_limited")]
    assert limited, "no plunge stopped by the holder beside the 70 mm walls"
    assert "held 60.0 mm from its tip in a 40.0 mm holder" in op.Summary
    broken = [b for b in plan.get("broken_limits", []) if b["limit"] == "stick_out"]
    assert broken and broken[0]["worst"] > 60.0
    # Replayed as posted: the holder never within its clearance of the stock
    # (the walls are stock the plunges never cut).
    program = read_program(compat.post_job(job, "linuxcnc", "--no-show-editor"))
    number = int(tcs[0].ToolNumber)
    holders = {number: [(60.0, 20.0)]}
    hits, worst, first = holder_hits(program, Stock(job.Stock.Shape.BoundBox, 0.5), tools_of(job), holders, 1.0)
    assert hits == 0, "%d moves bring the holder %.2f mm into its clearance, the first %s" % (hits, worst, first)
    # Without the holder, the same replay finds it in the walls: the check can fail.
    op.StickOut = 0.0
    doc.recompute()
    program = read_program(compat.post_job(job, "linuxcnc", "--no-show-editor"))
    hits, worst, _ = holder_hits(program, Stock(job.Stock.Shape.BoundBox, 0.5), tools_of(job), holders, 1.0)
    assert hits > 0 and worst > 5.0


def mount(bit, stick_out, holder):
    """What a user adds to a tool bit in the property editor (Add Property):
    its stick-out and its holder's diameter, as lengths."""
    for name, value in (("StickOut", stick_out), ("HolderDiameter", holder)):
        if not hasattr(bit, name):
            bit.addProperty("App::PropertyLength", name, "Attributes", "as mounted")
        setattr(bit, name, value)


@pytest.mark.bundle
def test_the_bits_own_holders_and_the_slim_tool_that_reaches(doc):
    """The holders come from the bits (no operation property set): the 20 mm
    plunger 60 mm out in a 40 mm holder stops beside the 70 mm walls, and the
    12 mm one, 95 mm out in a 32 mm holder, goes to the floor there. Both
    replayed as posted: no holder within its clearance."""
    job = parts.make_job(doc, deep_part())
    face = parts.floor_face_name(job.Model.Group[0].Shape, False)
    op, tcs = parts.add_plunge_rough(job, face, (20, 12), RadialAllowance=0.3, FloorAllowance=0.2,
                                     AutoSelectTools=False)
    mount(tcs[0].Tool, 60.0, 40.0)
    mount(tcs[1].Tool, 95.0, 32.0)
    op.recompute()
    doc.recompute()
    plan = PlungeRough.plan_of(op)
    assert plan is not None, op.Summary
    assert "held 60.0 mm from its tip in a 40.0 mm holder" in op.Summary, op.Summary
    assert "held 95.0 mm from its tip in a 32.0 mm holder" in op.Summary, op.Summary
    big, slim = int(tcs[0].ToolNumber), int(tcs[1].ToolNumber)
    assert any(p["tool_id"] == big and p.get("holder_limited") for p in plan["plunges"])
    # Beside the walls, where the 20 mm holder stops, the slim tool reaches the floor.
    floor = 10.0 + 0.2
    deep_at_walls = [p for p in plan["plunges"] if p["tool_id"] == slim and p["z"] < floor + 1e-6
                     and min(p["x"] - 20, 170 - p["x"], p["y"] - 20, 110 - p["y"]) < 21]
    assert len(deep_at_walls) > 20
    assert not [b for b in plan.get("broken_limits", []) if b["limit"] == "stick_out"], plan["broken_limits"]
    program = read_program(compat.post_job(job, "linuxcnc", "--no-show-editor"))
    holders = {big: [(60.0, 20.0)], slim: [(95.0, 16.0)]}
    hits, worst, first = holder_hits(program, Stock(job.Stock.Shape.BoundBox, 0.5), tools_of(job), holders, 1.0)
    assert hits == 0, "%d moves bring a holder %.2f mm into its clearance, the first %s" % (hits, worst, first)
