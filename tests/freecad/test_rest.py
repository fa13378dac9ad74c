"""Rest plunging (freecad_plugin/rest.py): Plunge Rough after other operations
of the Job, checked by replaying the Job's posted G-code, in order, on a fine
height field of the stock (gcode_replay.py, which shares no code with the
planner or the addon's replay)."""
import math

import FreeCAD
import Part
import pytest

import parts
from freecad_plugin import PlungeRough, compat, rest
from gcode_replay import Stock, part_surface, read_program, tools_of

V = FreeCAD.Vector
CELL = 0.5  # mm, the checker's height field


def pocket_block(width=120.0, length=80.0, depth=60.0, margin=20.0, below=10.0):
    """A block with a width x length pocket, depth deep (Part booleans)."""
    block = Part.makeBox(width + 2 * margin, length + 2 * margin, depth + below)
    cavity = Part.makeBox(width, length, depth + 1, V(margin, margin, below))
    return block.cut(cavity).removeSplitter()


def adaptive_module():
    for name in ("Path.Op.Adaptive", "PathScripts.PathAdaptive"):
        try:
            return __import__(name, fromlist=["Create"])
        except ImportError:
            continue
    raise ImportError("FreeCAD's Adaptive operation")


def set_value(obj, prop, value):
    """A property set by hand (its default expression, e.g. FinalDepth = OpFinalDepth, cleared)."""
    obj.setExpression(prop, None)
    setattr(obj, prop, value)


def adaptive_then_plunge(doc, cleared=20.0):
    """The Job a shop makes: FreeCAD's Adaptive clears the top `cleared` mm of
    the 60 mm pocket with a 16 mm end mill (T1), then Plunge Rough roughs the
    rest with the 20 mm plunger (T2). Built as the GUI builds it."""
    job = parts.make_job(doc, pocket_block())
    job.Stock.ExtZpos = 0  # a faced block
    doc.recompute()
    # FreeCAD 0.20 and 1.0 headless: an operation created in a Job with more
    # than one tool controller finds none (the GUI would ask): the default goes first.
    for default in list(job.Tools.Group):
        bit = default.Tool
        doc.removeObject(default.Name)
        doc.removeObject(bit.Name)
    end_mill = parts.add_tool_controller(job, 16, 1)
    end_mill.HorizFeed = "1200 mm/min"
    model = job.Model.Group[0]
    face = parts.floor_face_name(model.Shape, False)
    top = job.Stock.Shape.BoundBox.ZMax
    adaptive = adaptive_module().Create("Adaptive", parentJob=job)
    adaptive.ToolController = end_mill
    adaptive.Base = [(model, [face])]
    adaptive.OperationType, adaptive.Side, adaptive.StepOver = "Clearing", "Inside", 40
    adaptive.FinishingProfile = True  # its default: a last pass along the walls, no scallops left on them
    adaptive.StockToLeave = 0.5
    set_value(adaptive, "FinalDepth", top - cleared)
    set_value(adaptive, "StepDown", cleared)
    doc.recompute()
    assert len(adaptive.Path.Commands) > 10, "Adaptive made no path"
    plunger = parts.add_tool_controller(job, 20, 2)
    op = PlungeRough.Create("PlungeRough", parentJob=job)
    op.Base = [(model, [face])]
    op.ToolControllers = [plunger]
    op.RadialAllowance = 0.5
    doc.recompute()
    return job, adaptive, op


def program_of(job):
    return read_program(compat.post_job(job, "linuxcnc", "--no-show-editor"))


def minutes_of_tool(program, tool, rapid_rate):
    """Cycle minutes of one tool's moves: feeds at their F, rapids at rapid_rate."""
    total = 0.0
    for m in program.moves:
        if m.tool == tool:
            total += math.dist(m.a, m.b) / (rapid_rate if m.rapid else m.feed)
    return total


def plunge_checks(job, program, tool):
    """Replays the whole program on the stock: for each feed straight down of
    `tool`, the material it cut (mm3) and how far above the material under the
    tool its rapid down ended; what its rapids cut; the field at the end."""
    stock = Stock(job.Stock.Shape.BoundBox, CELL)
    tools = tools_of(job)
    cuts, heights, by_rapids = [], [], 0.0
    for prev, m in zip([None] + program.moves[:-1], program.moves):
        straight_down = m.a[0] == m.b[0] and m.a[1] == m.b[1] and m.b[2] < m.a[2]
        if m.tool == tool and not m.rapid and straight_down and prev is not None and prev.rapid:
            r = tools[tool][0]
            d = stock.xs[None, :] - m.a[0], stock.ys[:, None] - m.a[1]
            under = stock.z[(d[0] ** 2 + d[1] ** 2) <= (r - CELL) ** 2]
            heights.append(m.a[2] - under.max())
        v = stock.cut(m.a, m.b, tools[m.tool])
        if m.rapid and m.tool == tool:
            by_rapids += v
        elif m.tool == tool and straight_down:
            cuts.append(v)
    return cuts, heights, by_rapids, stock


@pytest.mark.bundle
@pytest.mark.parametrize("cleared", [20.0])
def test_plunge_rough_after_adaptive_plans_only_the_rest(doc, cleared):
    job, adaptive, op = adaptive_then_plunge(doc, cleared)
    assert op.RestFrom == rest.PREVIOUS, "rest plunging is the default after another operation"
    data = PlungeRough.companions.plan_data(op)
    stats = data["plan"]["stats"]
    assert stats["rest_material"] and "rest plunging" in op.Summary
    top = job.Stock.Shape.BoundBox.ZMax
    floor = top - 60.0
    # 60 mm of a 50 mm flute would take two levels: 40 mm left, one.
    assert stats["levels"] == 1
    program = program_of(job)
    cuts, heights, by_rapids, stock = plunge_checks(job, program, 2)
    assert cuts, "no plunge of the plunger in the posted program"
    print("%d plunges: each cut %.0f mm3 or more, its rapid down ended %.2f to %.2f mm above the material; "
          "rapids cut %.2f mm3" % (len(cuts), min(cuts), min(heights), max(heights), by_rapids))
    # No plunge cuts air: each takes at least a sliver of its own disk's
    # area (10 mm2) times the 1 mm it feeds from above the material.
    assert min(cuts) > 10.0, "a plunge cut %.1f mm3: air" % min(cuts)
    # Each rapid down stops just above the material the Adaptive left (the
    # planner's clearance, 1 mm, plus the checker's cell), never on the stock top.
    assert max(heights) < 1.0 + 2 * CELL + 1e-6, max(heights)
    assert min(heights) > 0.0, "a rapid down into material"
    assert by_rapids < 1.0, "rapids cut %.1f mm3" % by_rapids
    # The core is cut to the floor as without the Adaptive: the pocket less
    # allowance + wall band (0.5 + 1 mm) and a cell.
    inset = 0.5 + 1.0 + 2 * CELL
    x0, y0 = 20.0 + inset, 20.0 + inset
    core = ((stock.xs[None, :] > x0) & (stock.xs[None, :] < 140.0 - inset)
            & (stock.ys[:, None] > y0) & (stock.ys[:, None] < 100.0 - inset))
    assert (stock.z[core] <= floor + 0.01).mean() > 0.999
    # Against the same operation planning the whole pocket from the stock top:
    # at most 0.8 x the cycle time.
    rapid = op.ToolControllers[0].HorizRapid.getValueAs("mm/min").Value or 5000.0
    rest_minutes = minutes_of_tool(program, 2, rapid)
    op.RestFrom = rest.NONE
    doc.recompute()
    assert not PlungeRough.companions.plan_data(op)["plan"]["stats"]["rest_material"]
    full_minutes = minutes_of_tool(program_of(job), 2, rapid)
    print("Plunge Rough after Adaptive (top %g of 60 mm): %.2f min, whole pocket %.2f min (%.2f x)"
          % (cleared, rest_minutes, full_minutes, rest_minutes / full_minutes))
    assert rest_minutes <= 0.8 * full_minutes


def test_the_rest_solid_matches_the_replay(doc):
    """The rest material feature: the stock the Adaptive and the Plunge Rough
    leave, as a solid, against the replay of the Job's posted G-code."""
    job, adaptive, op = adaptive_then_plunge(doc)
    solid = rest.make_rest_solid(op)
    shape = solid.Shape
    assert shape.isValid() and shape.Volume > 0
    assert adaptive in solid.Sources and op in solid.Sources
    _, _, _, stock = plunge_checks(job, program_of(job), 2)
    box = job.Stock.Shape.BoundBox
    replayed = float((stock.z - box.ZMin).sum()) * CELL ** 2
    # Within the resolution: a cell's width along the pocket's walls (400 mm
    # around, 60 mm high) of the two rasters.
    assert abs(shape.Volume - replayed) < 400 * 60 * (CELL + 0.5), (shape.Volume, replayed)
    # And point by point, two of its cells (1.25 mm) and more from the walls:
    # the solid's top over the checker's cells.
    worst = 0.0
    for x, y in [(30.0, 30.0), (80.0, 60.0), (25.0, 60.0), (80.0, 95.0), (10.0, 60.0), (150.0, 110.0)]:
        i, j = int((x - stock.x0) // CELL), int((y - stock.y0) // CELL)
        line = Part.LineSegment(V(x, y, box.ZMax + 1), V(x, y, box.ZMin - 1)).toShape()
        top = max(v.Point.z for v in shape.section(line).Vertexes)
        worst = max(worst, abs(top - stock.z[j, i]))
    assert worst < 0.5, worst
    # After the Adaptive changes, the operation plans again (it is linked to
    # it) and its rest with it.
    before = solid.Shape.Volume
    set_value(adaptive, "FinalDepth", box.ZMax - 30.0)
    set_value(adaptive, "StepDown", 30.0)
    doc.recompute()
    plunges = PlungeRough.companions.plan_data(op)["plan"]["plunges"]
    assert max(p["approach_z"] for p in plunges) < box.ZMax - 28.0
    # Recomputed after them: the Adaptive's last pass along the walls now
    # also takes the plunges' scallops from 10 mm more of them.
    assert solid.Shape.Volume < before - 100.0


def test_a_second_plunge_rough_plans_only_the_rest(doc):
    """Two Plunge Roughs: the 20 mm plunger roughs a pocket with sharp corners,
    then an 8 mm plunger takes only what it left (the corners)."""
    job = parts.make_job(doc, pocket_block(depth=30.0))
    job.Stock.ExtZpos = 0
    doc.recompute()
    model = job.Model.Group[0]
    face = parts.floor_face_name(model.Shape, False)
    first, (big,) = parts.add_plunge_rough(job, face, (20,), RadialAllowance=0.5)
    small = parts.add_tool_controller(job, 8, 3)
    second = PlungeRough.Create("PlungeRough", parentJob=job)
    second.Base = [(model, [face])]
    second.ToolControllers = [small]
    second.RadialAllowance = 0.5
    doc.recompute()
    assert second.RestFrom == rest.PREVIOUS and first in second.RestSources
    stats = PlungeRough.companions.plan_data(second)["plan"]["stats"]
    assert stats["air_plunges"] > 50
    # Against the same 8 mm operation alone on the full stock.
    alone = PlungeRough.companions.plan_data(second)["plan"]["plunges"]
    second.RestFrom = rest.NONE
    doc.recompute()
    full = PlungeRough.companions.plan_data(second)["plan"]["plunges"]
    assert len(alone) < 0.2 * len(full), (len(alone), len(full))
    second.RestFrom = rest.PREVIOUS
    doc.recompute()
    program = program_of(job)
    cuts, heights, by_rapids, stock = plunge_checks(job, program, 3)
    print("second pass: %d plunges of 8 mm (alone %d), each cut %.1f mm3 or more, rapids cut %.2f mm3"
          % (len(cuts), len(full), min(cuts), by_rapids))
    assert min(cuts) > 1.0, "a plunge of the second pass cut air"
    assert by_rapids < 1.0
    # Every plunge of the second pass is in a corner: where the 20 mm left material.
    for p in PlungeRough.companions.plan_data(second)["plan"]["plunges"]:
        near_x = min(p["x"] - 20.0, 140.0 - p["x"]) < 15.0
        near_y = min(p["y"] - 20.0, 100.0 - p["y"]) < 15.0
        assert near_x and near_y, (p["x"], p["y"])


def cored_casting():
    """A casting: the block with its pocket cored 4 mm inside the final walls
    and 6 mm above the floor, drawn as a user draws one (Part boxes and a
    fillet on the core's vertical edges)."""
    block = Part.makeBox(160, 120, 70)
    core = Part.makeBox(112, 72, 60, V(24, 24, 16))
    core = core.makeFillet(6, [e for e in core.Edges if abs(e.Vertexes[0].Point.z - e.Vertexes[1].Point.z) > 1])
    return block.cut(core)


def test_a_cored_casting_is_plunged_only_where_it_has_material(doc):
    job = parts.make_job(doc, pocket_block())
    casting = doc.addObject("Part::Feature", "Casting")
    casting.Shape = cored_casting()
    doc.recompute()
    # As the Job panel's "existing solid" stock does it.
    stock = compat.PathJob.createResourceClone(job, casting, "Stock", "Stock")
    doc.removeObject(job.Stock.Name)
    job.Stock = stock
    doc.recompute()
    face = parts.floor_face_name(job.Model.Group[0].Shape, False)
    op, _ = parts.add_plunge_rough(job, face, (20, 10), RadialAllowance=0.5)
    assert op.RestFrom == rest.STOCK
    plan = PlungeRough.companions.plan_data(op)["plan"]
    assert plan["stats"]["rest_material"]
    # Inside the core the casting stands 6 mm above the floor: the plunges
    # there rapid down to just above it, not to the block's top.
    inner = [p for p in plan["plunges"] if 40 < p["x"] < 120 and 40 < p["y"] < 80]
    assert inner and max(p["approach_z"] for p in inner) <= 16.0 + 1.0 + 1e-6
    program = program_of(job)
    checker = Stock(job.Stock.Shape.BoundBox, CELL)
    # The casting's top over each cell (a fine mesh: not rest.py's), then the program.
    checker.z[:] = part_surface(casting.Shape, checker, empty=job.Stock.Shape.BoundBox.ZMin)
    tools = tools_of(job)
    casting_field = checker.z.copy()
    cut_of_plunge = []
    for m in program.moves:
        if not m.rapid and m.a[:2] == m.b[:2] and m.b[2] < m.a[2]:
            # What it cuts of the casting as it was before the operation (its
            # own other plunges may have taken the rest of a covering's sliver).
            probe = Stock(job.Stock.Shape.BoundBox, CELL)
            probe.z = casting_field.copy()
            cut_of_plunge.append(probe.cut(m.a, m.b, tools[m.tool]))
        v = checker.cut(m.a, m.b, tools[m.tool])
        if m.rapid:
            assert v < 1.0, "a rapid cut %.1f mm3" % v
    print("cored casting: %d plunges, each cut %.1f mm3 or more" % (len(cut_of_plunge), min(cut_of_plunge)))
    assert min(cut_of_plunge) > 1.0
    # The core is cut to the floor all the same.
    inset = 0.5 + 1.0 + 2 * CELL
    core = ((checker.xs[None, :] > 20 + inset) & (checker.xs[None, :] < 140 - inset)
            & (checker.ys[:, None] > 20 + inset) & (checker.ys[:, None] < 100 - inset))
    assert (checker.z[core] <= 10.0 + 0.01).mean() > 0.999
