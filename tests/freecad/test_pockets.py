"""Real pockets, modelled as a user models them (Part boxes, cuts and fillets,
the part placed off the origin), planned from the faces a user selects, posted
with linuxcnc and the G-code checked against the part's own solid (part_check)."""
import json
import math
import os

import FreeCAD
import Part
import pytest

import parts
from part_check import check
from freecad_plugin import companions, plan_files, PlungeRough
from freecad_plugin.compat import PathJob, post_job
from gcode import parse_gcode

V = FreeCAD.Vector
RADIAL, FLOOR, BAND = 0.5, 0.3, 1.0
PICTURES = os.environ.get("PLUNGE_POCKET_PICTURES")  # a folder: keep each case's plan picture there


def box(doc, name, x, y, z, at=(0, 0, 0)):
    b = doc.addObject("Part::Box", name)
    b.Length, b.Width, b.Height = x, y, z
    b.Placement.Base = V(*at)
    return b


def cut(doc, name, base, tool):
    c = doc.addObject("Part::Cut", name)
    c.Base, c.Tool = base, tool
    doc.recompute()
    return c


def fillet(doc, name, base, radius, pick):
    """Part Fillet of the edges of base whose bounding box pick() accepts."""
    f = doc.addObject("Part::Fillet", name)
    f.Base = base
    f.Edges = [(i + 1, radius, radius) for i, e in enumerate(base.Shape.Edges) if pick(e.BoundBox)]
    assert f.Edges
    base.Visibility = False
    doc.recompute()
    return f


def placed(obj):
    """The part as the user placed it: moved and turned about Z."""
    obj.Placement = FreeCAD.Placement(V(15, -7, 3), FreeCAD.Rotation(V(0, 0, 1), 15))
    obj.Document.recompute()
    return obj


def filleted_pocket(doc):
    """120 x 90 x 30 block, an 80 x 50 pocket 20 deep with 6 mm corner radii and
    a 3 mm fillet between floor and walls."""
    cavity = fillet(doc, "Corners", box(doc, "Cavity", 80, 50, 40, (20, 20, 10)), 6,
                    lambda b: b.ZLength > 1)
    pocket = cut(doc, "Pocket", box(doc, "Block", 120, 90, 30), cavity)
    return placed(fillet(doc, "Fillet", pocket, 3,
                         lambda b: abs(b.ZMin - 10) < 1e-6 and abs(b.ZMax - 10) < 1e-6 and 20 <= b.XMin <= b.XMax <= 100
                         and 20 <= b.YMin <= b.YMax <= 70))


def pocket_in_pocket(doc):
    """140 x 100 x 40 block, a 100 x 60 pocket 10 deep, inside it a 40 x 30 pocket
    25 deep with 4 mm corner radii."""
    inner = fillet(doc, "InnerCorners", box(doc, "Inner", 40, 30, 40, (50, 35, 15)), 4, lambda b: b.ZLength > 1)
    shallow = cut(doc, "Shallow", box(doc, "Block", 140, 100, 40), box(doc, "Outer", 100, 60, 20, (20, 20, 30)))
    return placed(cut(doc, "Pockets", shallow, inner))


def step(doc):
    """100 x 60 x 30 block with a 40 x 30 step 10 deep open on one side."""
    return placed(cut(doc, "Step", box(doc, "Block", 100, 60, 30), box(doc, "Cutout", 40, 30, 20, (60, 15, 20))))


def slot(doc):
    """100 x 60 x 30 block with a 30 wide slot 15 deep, through on two sides."""
    return placed(cut(doc, "Slot", box(doc, "Block", 100, 60, 30), box(doc, "Cutout", 30, 80, 20, (35, -10, 15))))


def faces_at(shape, z, planar=True):
    """Names of the horizontal faces at height z (placed part)."""
    out = []
    for i, f in enumerate(shape.Faces):
        if isinstance(f.Surface, Part.Plane) and abs(abs(f.Surface.Axis.z) - 1) < 1e-9 and abs(f.BoundBox.ZMin - z) < 1e-6:
            out.append("Face%d" % (i + 1))
    return out


def job_with_op(doc, obj, faces, **properties):
    """A Job on the modelled part, 12/8/5 mm plungers and Plunge Rough on the faces."""
    job = PathJob.Create("Job", [obj])
    doc.recompute()
    model = job.Model.Group[0]
    tcs = [parts.add_tool_controller(job, d, i + 2) for i, d in enumerate((12, 8, 5))]
    op = PlungeRough.Create("PlungeRough", parentJob=job)
    op.Base = [(model, faces)]
    op.RadialAllowance, op.FloorAllowance = RADIAL, FLOOR
    for name, value in properties.items():
        setattr(op, name, value)
    doc.recompute()
    return job, op, tcs


def check_job(job, op, tcs, levels):
    """Post with linuxcnc and check the G-code against the part; the findings."""
    plan = PlungeRough.plan_of(op)
    assert plan is not None, op.Summary
    if PICTURES:
        os.makedirs(PICTURES, exist_ok=True)
        with open(plan_files.plan_picture(op)) as f, \
                open(os.path.join(PICTURES, "%s.svg" % job.Document.Name.lower()), "w") as g:
            g.write(f.read())
    text = post_job(job, "linuxcnc", "--no-header --no-show-editor")
    model = job.Model.Group[0].Shape
    seeds = []
    for z in levels:
        face = next(model.getElement(n) for n in faces_at(model, z) if n in op.Base[0][1]
                    or not op.Base[0][1])
        seeds.append((face.CenterOfMass.x, face.CenterOfMass.y))
    # The floor stock asked for, or without the floor-stock step what the plan
    # says it leaves: either way the G-code must leave no more.
    limit = op.MaxFloorStock.Value or plan["stats"]["max_floor_stock_left"] + 0.01
    report = check(model, job.Stock.Shape.BoundBox.ZMax, text, {int(tc.ToolNumber): float(tc.Tool.Diameter)
                                                                 for tc in tcs},
                   RADIAL, FLOOR, BAND, limit, levels, seeds)
    assert report["plunges"] == plan["stats"]["plunge_count"]
    return plan, report


def assert_clean(report):
    assert not report["gouges"], report["gouges"][:5]
    assert not report["rapids_through_stock"], report["rapids_through_stock"][:5]
    assert not report["uncut"], report["uncut"][:5]


@pytest.fixture
def doc(request):
    d = FreeCAD.newDocument(request.node.name.replace("[", "_").replace("]", "").replace("-", "_"))
    name = d.Name
    yield d
    FreeCAD.closeDocument(name)


def floor_z(obj, z):
    return obj.Shape.BoundBox.ZMin + z  # heights above the block's bottom, placed


# Along the walls the fillet keeps rising beyond a plunge's rim: the radial
# allowance holds beside the tool as the floor allowance holds under it.
@pytest.mark.parametrize("with_fillets", [False, True])
def test_filleted_pocket_roughed_to_the_walls(doc, with_fillets):
    obj = filleted_pocket(doc)
    z = floor_z(obj, 10)
    floor = faces_at(obj.Shape, z)
    assert len(floor) == 1
    faces = list(floor)
    if with_fillets:  # the user picks the fillets too: the same pocket
        faces += ["Face%d" % (i + 1) for i, f in enumerate(obj.Shape.Faces)
                  if not isinstance(f.Surface, Part.Plane) and f.BoundBox.ZMax <= z + 3 + 1e-6]
    job, op, tcs = job_with_op(doc, obj, faces)
    plan, report = check_job(job, op, tcs, [z])
    assert_clean(report)
    assert "fillets added to the floor" in op.Summary or with_fillets
    # Roughed to the walls: plunges reach the fillets, stopping above them.
    zs = [p["z"] for p in plan["plunges"]]
    assert min(zs) == pytest.approx(z + FLOOR) and max(zs) > z + FLOOR + 0.5


def test_filleted_pocket_without_its_fillets_keeps_them(doc):
    obj = filleted_pocket(doc)
    z = floor_z(obj, 10)
    job, op, tcs = job_with_op(doc, obj, faces_at(obj.Shape, z), IncludeFillets=False)
    plan, report = check_job(job, op, tcs, [z])
    assert not report["gouges"] and not report["rapids_through_stock"]
    assert "fillets added" not in op.Summary
    # The fillets are walls now: no plunge cuts into them, and the pocket, wider
    # above its floor, keeps the wall band there too (sections of the part), so
    # nothing is left that the band and the floor stock do not excuse.
    sections = json.loads(op.PlanData)["input"]["sections"]
    assert sections and all(z < s["z"] <= z + 3 + 1e-6 for s in sections)
    assert not report["uncut"], report["uncut"]


@pytest.mark.parametrize("selection", ["shallow", "both"])
def test_pocket_in_a_pocket(doc, selection):
    obj = pocket_in_pocket(doc)
    shallow, deep = floor_z(obj, 30), floor_z(obj, 15)
    faces = faces_at(obj.Shape, shallow) + (faces_at(obj.Shape, deep) if selection == "both" else [])
    job, op, tcs = job_with_op(doc, obj, faces)
    levels = [shallow] if selection == "shallow" else [shallow, deep]
    assert op.FinalDepth.Value == pytest.approx(min(levels))  # the lowest selected face
    plan, report = check_job(job, op, tcs, levels)
    assert_clean(report)
    data = json.loads(op.PlanData)["input"]
    assert data["islands"] == []  # the deeper pocket is no island, and no slivers
    zs = sorted(p["z"] for p in plan["plunges"])
    assert zs[0] == pytest.approx(min(levels) + FLOOR)
    if selection == "shallow":
        assert "1 hole where the part goes deeper" in op.Summary


@pytest.mark.parametrize("make, sides", [(step, 1), (slot, 2)])
def test_open_sides_leave_no_skin(doc, make, sides):
    obj = make(doc)
    z = min(f.BoundBox.ZMin for f in obj.Shape.Faces
            if isinstance(f.Surface, Part.Plane) and f.BoundBox.ZMin > obj.Shape.BoundBox.ZMin + 1e-6)
    job, op, tcs = job_with_op(doc, obj, faces_at(obj.Shape, z))
    plan, report = check_job(job, op, tcs, [z])
    assert_clean(report)
    assert "%d open side" % sides in op.Summary
    # Plunges reach past the open sides: a point of their rim is off the part
    # (1 mm under the floor the part is its whole block, so "off the part" is
    # past its outline).
    def past_the_part(p):
        r = p["diameter"] / 2
        return any(not obj.Shape.isInside(V(p["x"] + r * math.cos(a), p["y"] + r * math.sin(a), z - 1), 1e-6, True)
                   for a in (2 * math.pi * k / 36 for k in range(36)))
    assert sum(1 for p in plan["plunges"] if past_the_part(p)) >= sides


def test_wall_selected_by_mistake(doc):
    obj = pocket_in_pocket(doc)
    wall = next("Face%d" % (i + 1) for i, f in enumerate(obj.Shape.Faces) if isinstance(f.Surface, Part.Cylinder))
    job, op, tcs = job_with_op(doc, obj, [wall])
    assert PlungeRough.plan_of(op) is None
    assert "is a wall" in op.Summary and "select the pocket's floor" in op.Summary


def test_refused_operation_posts_no_tool_change(doc):
    obj = pocket_in_pocket(doc)
    wall = next("Face%d" % (i + 1) for i, f in enumerate(obj.Shape.Faces) if isinstance(f.Surface, Part.Cylinder))
    job, op, tcs = job_with_op(doc, obj, faces_at(obj.Shape, floor_z(obj, 30)))
    assert PlungeRough.plan_of(op) is not None
    op.Base = [(job.Model.Group[0], [wall])]
    doc.recompute()
    assert PlungeRough.plan_of(op) is None
    text = post_job(job, "linuxcnc", "--no-header --no-show-editor")
    # The companions (8 and 5 mm) write no tool change and no move.
    changes = [int(w["T"]) for codes, w in parse_gcode(text) if "M6" in codes and "T" in w]
    assert 3 not in changes and 4 not in changes
    assert not any(c.Active for c in companions.companions(op))
    # Selecting the floor again brings them back.
    op.Base = [(job.Model.Group[0], faces_at(obj.Shape, floor_z(obj, 30)))]
    doc.recompute()
    plan = PlungeRough.plan_of(op)
    assert plan is not None
    # Those of the plungers the plan uses (the tool choice is on for new operations).
    used = {t["tool_id"] for t in plan["stats"]["per_tool"]}
    assert [c.Active for c in companions.companions(op)] == [
        int(c.ToolController.ToolNumber) in used for c in companions.companions(op)]
