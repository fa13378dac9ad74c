"""The whole part: material over the floor that the floor's outline does not
show (a tab out of a wall, a dome wider than its stem), modelled as a user
models it (Part boxes, a sphere and a cylinder, fused and cut, the part placed
off the origin and turned), planned from the floor a user selects, posted with
linuxcnc and the G-code checked against the part's own solid (part_check):
no plunge, lead-out or rapid enters it."""
import json
import os
import random
import re

import pytest

import FreeCAD
import Part

from freecad_plugin import PlungeRough
from freecad_plugin.compat import post_job
from part_check import check
from test_pockets import FLOOR, RADIAL, assert_clean, box, check_job, cut, doc, faces_at, floor_z, job_with_op, placed  # noqa: F401

V = FreeCAD.Vector


def fuse(doc, name, shapes):
    f = doc.addObject("Part::MultiFuse", name)
    f.Shapes = shapes
    doc.recompute()
    return f


def tab_over_pocket(doc):
    """120 x 90 x 30 block, an 80 x 50 pocket 20 deep, and a 25 x 20 x 5 tab out
    of its left wall, 4 mm below the top: the floor's outline is a rectangle."""
    pocket = cut(doc, "Pocket", box(doc, "Block", 120, 90, 30), box(doc, "Cavity", 80, 50, 40, (20, 20, 10)))
    return placed(fuse(doc, "WithTab", [pocket, box(doc, "Tab", 25, 20, 5, (20, 35, 21))]))


def dome_on_stem(doc):
    """140 x 100 x 50 block, a 100 x 70 pocket 40 deep, and in it a stem of
    R 11.5 carrying a dome of R 15.9 whose top is 2 mm below the part's (a
    sphere on a cylinder, fused): the floor's outline shows the stem only."""
    pocket = cut(doc, "Pocket", box(doc, "Block", 140, 100, 50), box(doc, "Cavity", 100, 70, 50, (20, 15, 10)))
    stem = doc.addObject("Part::Cylinder", "Stem")
    stem.Radius, stem.Height = 11.5, 20
    stem.Placement.Base = V(55, 45, 10)
    ball = doc.addObject("Part::Sphere", "Dome")
    ball.Radius = 15.9
    ball.Placement.Base = V(55, 45, 48 - 15.9)  # widest 22.1 mm above the floor
    return placed(fuse(doc, "WithDome", [pocket, stem, ball]))


@pytest.mark.bundle
@pytest.mark.parametrize("make", [tab_over_pocket, dome_on_stem])
def test_no_plunge_goes_into_material_over_the_floor(doc, make):
    obj = make(doc)
    z = floor_z(obj, 10)
    faces = faces_at(obj.Shape, z)
    assert len(faces) == 1
    # Not pecked: the check counts each plunge once.
    job, op, tcs = job_with_op(doc, obj, faces, PeckEnabled=False)
    plan, report = check_job(job, op, tcs, [z])
    assert_clean(report)
    assert "overhangs the pocket" in op.Summary, op.Summary
    # Roughed up to it: the plunges reach the overhang's shadow.
    assert len(plan["plunges"]) > 20
    assert min(p["z"] for p in plan["plunges"]) == pytest.approx(z + FLOOR)
    assert "part" in json.loads(op.PlanData)["input"]
    assert PlungeRough.plan_of(op) is not None


def housing_with_window(doc):
    """120 x 80 x 50 housing, a 100 x 60 cavity 40 deep, and a 30 mm window
    through its floor from wall to wall: the floor is two strips."""
    housing = cut(doc, "Housing", box(doc, "Block", 120, 80, 50), box(doc, "Cavity", 100, 60, 50, (10, 10, 10)))
    return placed(cut(doc, "WithWindow", housing, box(doc, "Window", 30, 60, 20, (45, 10, -5))))


def pocket_with_trough(doc):
    """120 x 80 x 40 block, a 100 x 60 pocket 30 deep, and along its back wall
    a trough 12 wide and 6 deeper: the floor's outline steps down along it."""
    pocket = cut(doc, "Pocket", box(doc, "Block", 120, 80, 40), box(doc, "Cavity", 100, 60, 40, (10, 10, 10)))
    return placed(cut(doc, "WithTrough", pocket, box(doc, "Trough", 100, 12, 10, (10, 58, 4))))


@pytest.mark.parametrize("make, strips", [(housing_with_window, 2), (housing_with_window, 1), (pocket_with_trough, 1)])
def test_the_cavity_over_a_window_or_a_trough_is_one_pocket(doc, make, strips):
    obj = make(doc)
    z = floor_z(obj, 10)
    faces = faces_at(obj.Shape, z)
    assert len(faces) == (2 if make is housing_with_window else 1)
    job, op, tcs = job_with_op(doc, obj, faces[:strips], PeckEnabled=False)
    plan, report = check_job(job, op, tcs, [z])
    assert_clean(report)
    assert "the cavity around the floor planned whole" in op.Summary, op.Summary
    assert "separate floors" not in op.Summary and "kept as walls" not in op.Summary
    # Plunges over the window or the trough, as deep as the floor around it.
    model = obj.Shape
    over = [p for p in plan["plunges"]
            if not model.isInside(V(p["x"], p["y"], z - 0.5), 1e-6, True)]
    assert over and all(p["z"] == pytest.approx(z + FLOOR) for p in over)


# What a refusal may not look like: Python's own words, or the planner's input
# keys (internal messages a user cannot act on).
INTERNAL = re.compile(r"Traceback|NoneType|has no attribute|arg is an empty sequence|index out of range|"
                      r"sections\[|islands\[|island \d+:|boundary:|not subscriptable|unexpected keyword")
# Every refusal ends in what to do.
ACTIONABLE = re.compile(r"select|refine|use |add |raise |lower |set |turn ", re.IGNORECASE)
SELECTIONS = 4 if os.environ.get("PLUNGE_LONG_TESTS") == "1" else 2


@pytest.mark.parametrize("make", [tab_over_pocket, dome_on_stem, housing_with_window, pocket_with_trough])
def test_any_selection_plans_or_says_what_to_do(doc, make):
    """Random faces and face sets of the part, as a user may click them: each
    plans, or is refused in one line that names the problem and what to do."""
    obj = make(doc)
    faces = obj.Shape.Faces
    # Mostly faces one could plunge onto (not standing walls), some of any kind.
    upright = [isinstance(f.Surface, Part.Plane) and abs(f.Surface.Axis.z) < 1e-9
               or isinstance(f.Surface, Part.Cylinder) and abs(abs(f.Surface.Axis.z) - 1) < 1e-9 for f in faces]
    lying = [i + 1 for i in range(len(faces)) if not upright[i]]
    rng = random.Random(make.__name__)

    def pick():
        return rng.choice(lying) if rng.random() < 0.8 else rng.randint(1, len(faces))
    picks = [["Face%d" % pick()] for _ in range(SELECTIONS)]
    picks += [sorted({"Face%d" % pick() for _ in range(rng.randint(2, 3))}) for _ in range(SELECTIONS)]
    picks = [list(p) for p in dict.fromkeys(map(tuple, picks))]  # a selection made again tells nothing new
    job, op, tcs = job_with_op(doc, obj, picks[0], PeckEnabled=False)
    for names in picks:
        op.Base = [(job.Model.Group[0], names)]
        doc.recompute()
        summary = op.Summary
        print("selected", names, ":", summary[:200])
        assert not INTERNAL.search(summary), (names, summary)
        if PlungeRough.plan_of(op) is None:
            assert "\n" not in summary.strip() and ACTIONABLE.search(summary), (names, summary)


def tapered_bosses(doc):
    """140 x 100 x 40 block, a 100 x 70 pocket 20 deep open at its front, on its
    floor two bosses tapering from R 15.9 to R 12.1 (Part cones) and a rib
    with a sloped top (a Part wedge): the floor's outline shows their feet."""
    pocket = cut(doc, "Pocket", box(doc, "Block", 140, 100, 40), box(doc, "Cavity", 100, 90, 40, (20, -10, 20)))
    shapes = [pocket]
    for i, x in enumerate((50, 110)):
        cone = doc.addObject("Part::Cone", "Boss%d" % i)
        cone.Radius1, cone.Radius2, cone.Height = 15.9, 12.1, 18
        cone.Placement.Base = V(x, 50, 20)
        shapes.append(cone)
    rib = doc.addObject("Part::Wedge", "Rib")
    rib.Xmin, rib.Xmax, rib.Ymin, rib.Ymax, rib.Zmin, rib.Zmax = 0, 8, 0, 16, 0, 40
    rib.X2min, rib.X2max, rib.Z2min, rib.Z2max = 0, 8, 0, 12  # 16 high at its back, 4 at its front
    rib.Placement = FreeCAD.Placement(V(76, 70, 20), FreeCAD.Rotation(V(1, 0, 0), 90))
    shapes.append(rib)
    return placed(fuse(doc, "WithBosses", shapes))


def test_the_stock_around_islands_that_narrow_upward_is_said(doc):
    obj = tapered_bosses(doc)
    z = floor_z(obj, 20)
    faces = faces_at(obj.Shape, z)
    assert len(faces) == 1
    job, op, tcs = job_with_op(doc, obj, faces, PeckEnabled=False)
    plan, report = check_job(job, op, tcs, [z])
    assert not report["gouges"] and not report["rapids_through_stock"], report
    assert "open side" in op.Summary
    said = [b for b in plan["broken_limits"] if b["limit"] == "max_wall_stock"]
    # Beside the bosses and the rib's ramp the pocket is wider above its floor
    # than its outline: said at its size (the rings between the heights that
    # get plunges: a few mm; the ramp's end, up to about its run over the
    # band's height), never more than the pocket's half width.
    worst = max((b["worst"] for b in said), default=0.0)
    assert 2.0 < worst < 35.0, op.Summary
    assert any("measured against the whole part" in w or "just below" in w for w in plan["warnings"]), op.Summary
    # The summary's walls figure says it too.
    assert plan["stats"]["max_wall_stock_left"] == pytest.approx(worst)
    assert "walls up to %.2f mm" % worst in op.Summary


def tilted_floor_with_standoffs(doc):
    """140 x 100 x 50 block, a 100 x 70 pocket whose floor is tilted 8 degrees
    about X, and on it three standoffs (Part cylinders R 5 up to 6 mm below the
    top): their feet on the tilted floor are ellipses, some of whose edges run
    against their curve's parameter."""
    cavity = box(doc, "Cavity", 100, 70, 60, (20, 15, 15))
    cavity.Placement = FreeCAD.Placement(V(20, 15, 15), FreeCAD.Rotation(V(1, 0, 0), 8))
    pocket = cut(doc, "Pocket", box(doc, "Block", 140, 100, 50), cavity)
    shapes = [pocket]
    for i, (x, y) in enumerate(((45, 35), (95, 40), (70, 65))):
        c = doc.addObject("Part::Cylinder", "Standoff%d" % i)
        c.Radius, c.Height = 5, 40
        c.Placement.Base = V(x, y, 4)
        shapes.append(c)
    return placed(fuse(doc, "WithStandoffs", shapes))


def enclosure_base(doc):
    """An enclosure's base: 140 x 100 x 30 block, a 110 x 70 pocket 20 deep with
    a 45 degree chamfer of 3 mm along its floor's edges (Part Chamfer) and four
    bosses R 6 in its corners."""
    pocket = cut(doc, "Pocket", box(doc, "Block", 140, 100, 30), box(doc, "Cavity", 110, 70, 40, (15, 15, 10)))
    ch = doc.addObject("Part::Chamfer", "Chamfer")
    ch.Base = pocket
    ch.Edges = [(i + 1, 3.0, 3.0) for i, e in enumerate(pocket.Shape.Edges)
                if abs(e.BoundBox.ZMin - 10) < 1e-6 and abs(e.BoundBox.ZMax - 10) < 1e-6
                and 15 <= e.BoundBox.XMin and e.BoundBox.XMax <= 125 and 15 <= e.BoundBox.YMin and e.BoundBox.YMax <= 85]
    pocket.Visibility = False
    doc.recompute()
    shapes = [ch]
    for i, (x, y) in enumerate(((28, 28), (112, 28), (28, 72), (112, 72))):
        c = doc.addObject("Part::Cylinder", "Boss%d" % i)
        c.Radius, c.Height = 6, 20
        c.Placement.Base = V(x, y, 10)
        shapes.append(c)
    return placed(fuse(doc, "Base", shapes))


@pytest.mark.parametrize("make", [tilted_floor_with_standoffs, enclosure_base])
def test_curved_and_chamfered_outlines_plan(doc, make):
    obj = make(doc)
    # The floor: the largest face looking up at the cavity's bottom.
    def up(f):
        u0, u1, v0, v1 = f.ParameterRange
        return f.normalAt(0.5 * (u0 + u1), 0.5 * (v0 + v1)).z
    floor = max((f for f in obj.Shape.Faces if isinstance(f.Surface, Part.Plane) and up(f) > 0.9
                 and f.BoundBox.ZMax < obj.Shape.BoundBox.ZMax - 1), key=lambda f: f.Area)
    name = "Face%d" % (next(i for i, f in enumerate(obj.Shape.Faces) if f.isSame(floor)) + 1)
    job, op, tcs = job_with_op(doc, obj, [name], PeckEnabled=False)
    plan = PlungeRough.plan_of(op)
    assert plan is not None, op.Summary
    assert not INTERNAL.search(op.Summary), op.Summary
    data = json.loads(op.PlanData)["input"]
    assert len(data["islands"]) >= 3  # the standoffs' or the bosses' feet
    gcode = post_job(job, "linuxcnc", "--no-header --no-show-editor")
    report = check(job.Model.Group[0].Shape, job.Stock.Shape.BoundBox.ZMax, gcode,
                   {int(tc.ToolNumber): float(tc.Tool.Diameter) for tc in tcs}, RADIAL, FLOOR, 1.0, 10.0, [], [])
    assert not report["gouges"] and not report["rapids_through_stock"], report


def four_slots(doc):
    """120 x 100 x 30 block with four slots 12 wide and 15 deep, open at both
    ends (Part cuts of boxes through it)."""
    shape = box(doc, "Block", 120, 100, 30)
    for i, x in enumerate((15, 40, 65, 90)):
        shape = cut(doc, "Slot%d" % i, shape, box(doc, "SlotTool%d" % i, 12, 120, 20, (x, -10, 15)))
    return placed(shape)


def test_separate_floors_are_counted_right(doc):
    obj = four_slots(doc)
    floors = faces_at(obj.Shape, floor_z(obj, 15))
    assert len(floors) == 4
    job, op, tcs = job_with_op(doc, obj, floors, PeckEnabled=False)
    assert PlungeRough.plan_of(op) is None
    assert "make 4 separate floors" in op.Summary, op.Summary
    # One of them plans, open at both ends.
    op.Base = [(job.Model.Group[0], floors[:1])]
    doc.recompute()
    assert PlungeRough.plan_of(op) is not None, op.Summary
    assert "2 open sides" in op.Summary


def test_chords_stay_within_the_chord_tolerance(doc):
    """The outline's chords (each chord's middle checked against the edges
    near it) never stray farther from the part's edges than the chord
    tolerance: measured here along every chord of every flat face's wire of
    the curved test parts, at five points each, by OpenCASCADE's own distance."""
    from freecad_plugin import geometry
    import parts
    shapes = [parts.freeform_part()] + [make(doc).Shape for make in (
        dome_on_stem, tilted_floor_with_standoffs, enclosure_base)]
    tolerance = 0.01
    checked = 0
    # The wires the planner's outlines come from: those of flat faces (floors,
    # their shadows, sections).
    for shape in shapes:
        for wire in (w for f in shape.Faces if isinstance(f.Surface, Part.Plane) for w in f.Wires):
            points, measured = geometry._chords(wire, tolerance)
            assert measured <= tolerance
            for a, b in zip(points, points[1:]):
                for k in (0.1, 0.3, 0.5, 0.7, 0.9):
                    assert wire.distToShape(Part.Vertex(a + (b - a) * k))[0] <= tolerance + 1e-7
                    checked += 1
    assert checked > 1000
