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
from gcode_replay import Stock, read_program, replay, tools_of

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
