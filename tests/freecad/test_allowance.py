"""The allowances in 3D, measured with OpenCASCADE (allowance_check): at every
stop of the posted Path, the flat, bull or ball tool's solid keeps the floor
allowance from every face of the part and the radial allowance from its
vertical walls (>= allowance - 0.005 mm), on pockets as users model them:
filleted rectangular pockets (Part makeFillet, R1 to R10, walls and floor
edges), corner blends (walls R5, then floor edges R2), the sculptured example
part, and a public part (NIST CTC-02, its filleted pockets found on the part).

Alone, with the suite's environment (tests/CMakeLists.txt): this file is its own
runner under freecadcmd (pytest on this file; PLUNGE_TESTS_K=<-k expression>):
  PLUNGE_SUITE=freecad PLUNGE_BUILD_DIR=build XDG_DATA_HOME=build/freecad-home/freecad/data \
  XDG_CONFIG_HOME=build/freecad-home/freecad/config freecadcmd tests/freecad/test_allowance.py
PLUNGE_ALLOWANCE_REPORTS=<folder>: each case's report as JSON there.
PLUNGE_NIST_PART=<file.stp>: the NIST part (default: NIST_PART below; skipped when missing)."""
import os
import sys

if "_pytest" not in sys.modules:  # run by freecadcmd as a script: pytest on this file
    import pytest
    sys.modules.pop(__name__, None)  # freecadcmd registered this script under the module's name
    args = ["-q", "-p", "no:cacheprovider", __file__]
    if os.environ.get("PLUNGE_TESTS_K"):
        args += ["-k", os.environ["PLUNGE_TESTS_K"]]
    code = int(pytest.main(args))
    sys.stdout.flush()
    sys.stderr.flush()
    sys.exit(code)

import json
import math
import re
import time

import FreeCAD
import Part
import pytest

import parts
import allowance_check as ac
from freecad_plugin import PlungeRough
from freecad_plugin import compat
from freecad_plugin.compat import PathJob, PathToolController, tool_bit_from_file

V = FreeCAD.Vector
RADIAL, FLOOR = 0.5, 0.3
HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
NIST_PART = os.environ.get("PLUNGE_NIST_PART",
                           os.path.join(ROOT, "tests", "data", "parts", "nist_ctc_02_asme1_rc.stp"))
REPORTS = os.environ.get("PLUNGE_ALLOWANCE_REPORTS")
# Every case runs where PLUNGE_LONG_TESTS=1 (CI's native run, .ci/run: about
# 15 minutes); elsewhere (the fresh chroots of the other FreeCAD versions) a
# quick few: one per tool shape, a B-spline blend, the band above fillets.
LONG = os.environ.get("PLUNGE_LONG_TESTS") == "1"
full = pytest.mark.skipif(not LONG, reason="a long case: PLUNGE_LONG_TESTS=1 runs it")
# The public part's pocket: 4400 plunges planned in about 3 minutes and measured
# in about 8 per tool shape; run by hand with PLUNGE_PUBLIC_PART_TESTS=1.
public_part = pytest.mark.skipif(os.environ.get("PLUNGE_PUBLIC_PART_TESTS") != "1",
                                 reason="tens of minutes: PLUNGE_PUBLIC_PART_TESTS=1 runs it")


def quick(*values, long=False):
    return pytest.param(*values, marks=full) if long else pytest.param(*values)
PLAN_SECONDS = {}  # planning time per operation, for the reports

# The plungers of each kind: (diameter, corner radius of the bull tools).
SETS = {"flat": [(10, 0), (6, 0)],
        "bull": [(10, 2), (6, 1)],
        "ball": [(10, 0), (6, 0)]}
SHAPES = {"flat": ("endmill.fcstd", "Endmill"), "bull": ("bullnose.fcstd", "Bullnose"),
          "ball": ("ballend.fcstd", "Ballend")}


@pytest.fixture
def doc(request):
    d = FreeCAD.newDocument("Allow_" + "".join(c if c.isalnum() else "_" for c in request.node.name))
    name = d.Name
    yield d
    FreeCAD.closeDocument(name)


# ---------------------------------------------------------------- tools

def write_bit(kind, diameter, corner, folder, flute=50.0, length=100.0):
    """A flat, bull-nose or ball-end bit file (.fctb) as FreeCAD's tool library
    editor writes one, from FreeCAD's own shapes."""
    os.makedirs(folder, exist_ok=True)
    shape, shape_type = SHAPES[kind]
    params = {"Diameter": "%g mm" % diameter, "ShankDiameter": "%g mm" % diameter,
              "CuttingEdgeHeight": "%g mm" % flute, "Length": "%g mm" % length}
    if kind == "bull":  # FreeCAD 1.1's bull nose takes its corner radius, older ones the flat's
        if compat.version() >= (1, 1):
            params["CornerRadius"] = "%g mm" % corner
        else:
            params["FlatRadius"] = "%g mm" % (diameter / 2.0 - corner)
    name = "%gmm_%s%s_%g" % (diameter, kind, "_r%g" % corner if kind == "bull" else "", length)
    path = os.path.join(folder, name + ".fctb")
    with open(path, "w") as f:
        json.dump({"version": 2, "name": name.replace("_", " "), "shape": shape, "shape-type": shape_type,
                   "parameter": params, "attribute": {}}, f, indent=2)
    return path


def add_plungers(job, kind, tools, folder, **bit):
    tcs = []
    for i, (d, rc) in enumerate(tools):
        tool = tool_bit_from_file(write_bit(kind, d, rc, folder, **bit), job.Document)
        tc = PathToolController.Create("TC: %g mm %s" % (d, kind), tool=tool, toolNumber=i + 2)
        tc.VertFeed = "150 mm/min"
        tc.HorizFeed = "600 mm/min"
        tc.SpindleSpeed = round(40000.0 / d)
        job.Proxy.addToolController(tc)
        tcs.append(tc)
    return tcs


def plan(doc, shape, floor_faces, kind, tmp, tools=None, placement=None, include_fillets=True, MaxFloorStock=1.0,
         **bit):
    """A Job on the shape (as a Part feature, placed), the kind's plungers and a
    Plunge Rough operation on the floor faces (fillets included), recomputed."""
    if isinstance(shape, Part.Shape):
        obj = doc.addObject("Part::Feature", "Part")
        obj.Shape = shape
    else:  # the part as a user modelled it (a feature of the document)
        obj = shape
    if placement is not None:
        obj.Placement = placement
    doc.recompute()
    job = PathJob.Create("Job", [obj])
    doc.recompute()
    model = job.Model.Group[0]
    tcs = add_plungers(job, kind, tools or SETS[kind], str(tmp), **bit)
    op = PlungeRough.Create("PlungeRough", parentJob=job)
    op.Base = [(model, floor_faces(model.Shape))]
    op.IncludeFillets = include_fillets
    op.MaxFloorStock = MaxFloorStock
    op.RadialAllowance, op.FloorAllowance = RADIAL, FLOOR
    t0 = time.time()
    doc.recompute()
    PLAN_SECONDS[op.Name] = time.time() - t0
    assert PlungeRough.plan_of(op) is not None, op.Summary
    return job, op, tcs


def measured(job, op, name):
    """The check of the Job's stops, cross-checked with the op's plan, saved
    when asked; asserts it passes."""
    report = ac.check_job(job, RADIAL, FLOOR)
    plan_ = PlungeRough.plan_of(op)
    # The Path holds the plan's plunges (the stops measured are the posted ones).
    assert report["stops"] == len({(p["tool_id"], round(p["x"], 5), round(p["y"], 5), round(p["z"], 5))
                                    for p in plan_["plunges"]})
    report["case"] = name
    report["summary"] = op.Summary
    report["plan_seconds"] = round(PLAN_SECONDS.get(op.Name, 0.0), 1)
    if REPORTS:
        os.makedirs(REPORTS, exist_ok=True)
        with open(os.path.join(REPORTS, name + ".json"), "w") as f:
            json.dump(report, f, indent=1, default=str)
    print("\n%s: %s" % (name, ac.describe(report)))
    assert report["failure_count"] == 0, ac.describe(report)
    return report


# ---------------------------------------------------------------- parts

def placed():
    return FreeCAD.Placement(V(15, -7, 3), FreeCAD.Rotation(V(0, 0, 1), 15))


def _floor_edge(b, z):
    return abs(b.ZMin - z) < 1e-6 and abs(b.ZMax - z) < 1e-6 and b.XMin > 1 and b.YMin > 1 and b.XMax < 89 \
        and b.YMax < 69


def box_pocket(wall_radius, floor_radius, together=True):
    """A 90 x 70 x 35 block with a 60 x 40 pocket 20 deep; its vertical edges
    filleted at wall_radius and its floor edges at floor_radius: in one
    makeFillet (together), or walls first, then the floor edges (corner blends)."""
    block = Part.makeBox(90, 70, 35)
    shape = block.cut(Part.makeBox(60, 40, 40, V(15, 15, 15))).removeSplitter()
    z = 15.0
    walls = [e for e in shape.Edges if e.BoundBox.ZLength > 19 and e.BoundBox.XLength < 1e-6
             and e.BoundBox.YLength < 1e-6 and 14 < e.BoundBox.XMin < 76 and 14 < e.BoundBox.YMin < 56]
    floor = [e for e in shape.Edges if _floor_edge(e.BoundBox, z)]
    assert len(walls) == 4 and len(floor) == 4
    if together:
        shape = shape.makeFillet(wall_radius, walls + floor)
    else:
        shape = shape.makeFillet(wall_radius, walls)
        floor = [e for e in shape.Edges if _floor_edge(e.BoundBox, z)]
        assert len(floor) == 8  # the straight edges and the corners' arcs
        shape = shape.makeFillet(floor_radius, floor)
    assert shape.isValid()
    return shape


def flat_up(face):
    """The height of a horizontal plane face facing up (out of the material), else None."""
    if not isinstance(face.Surface, Part.Plane) or abs(abs(face.Surface.Axis.z) - 1) > 1e-9:
        return None
    return face.Surface.Position.z if up_normal(face).z > 0 else None


def lowest_up_face(shape):
    """The pocket's flat floor: the lowest face facing up above the bottom."""
    best = None
    for i, f in enumerate(shape.Faces):
        z = flat_up(f)
        if z is not None and shape.BoundBox.ZMin + 1e-6 < z < shape.BoundBox.ZMax - 1e-6 \
                and (best is None or z < best[1]):
            best = ("Face%d" % (i + 1), z)
    return [best[0]]


def up_normal(face):
    u0, u1, v0, v1 = face.ParameterRange
    return face.normalAt(0.5 * (u0 + u1), 0.5 * (v0 + v1))


def pocket_floors(shape, min_area=100.0):
    """The pocket floors of a part: flat faces facing up, below the part's top,
    whose outer boundary has material rising above it all around (every face
    along the outer wire reaches higher). [(name, face, names of the non-planar
    neighbours: fillets)], largest first."""
    out = []
    top = shape.BoundBox.ZMax
    for i, f in enumerate(shape.Faces):
        z = flat_up(f)
        if z is None or f.Area < min_area or z > top - 1.0:
            continue
        walled, fillets = True, []
        for e in f.OuterWire.Edges:
            others = [o for o in shape.ancestorsOfType(e, Part.Face) if not o.isSame(f)]
            if not others or any(o.BoundBox.ZMax < z + 1.0 for o in others):
                walled = False
                break
            fillets += [o for o in others if not isinstance(o.Surface, Part.Plane)]
        if walled:
            names = sorted({"Face%d" % (j + 1) for j, g in enumerate(shape.Faces) for o in fillets if g.isSame(o)})
            out.append(("Face%d" % (i + 1), f, names))
    out.sort(key=lambda t: -t[1].Area)
    return out


# ---------------------------------------------------------------- the checker itself

def test_checker_tool_solids_and_distances():
    """Known distances: each tool 0.3 above a plane, beside a wall, over a 45 degree slope."""
    plane = Part.makePlane(100, 100, V(-50, -50, -0.3))
    slope = Part.makePlane(100, 100, V(0, -50, 0))
    slope.rotate(V(7, 0, 0), V(0, 1, 0), -45)  # rises to +X from (7, 0, 0)
    # The nearest point: the flat tool's rim, the bull's corner circle, the ball's centre.
    expect = {"flat": 1 * math.sqrt(0.5), "bull": (2.5 + 1.5) * math.sqrt(0.5) - 1.5,
              "ball": (7 + 6) * math.sqrt(0.5) - 6}
    for kind, rc in (("flat", 0), ("bull", 1.5), ("ball", 0)):
        tool = ac.Tool(kind, 6, rc, flute=50)
        s = tool.at(0, 0, 0, 50)
        assert s.isValid() and s.BoundBox.ZMin == pytest.approx(0, abs=1e-9)
        assert s.distToShape(plane)[0] == pytest.approx(0.3, abs=1e-7)
        assert s.distToShape(slope)[0] == pytest.approx(expect[kind], abs=1e-6)
        wall = Part.makeBox(1, 100, 60, V(6.5, -50, -5))
        assert s.distToShape(wall)[0] == pytest.approx(0.5, abs=1e-7)
        # The sweep: its volume is both ends and the section's prism between them.
        swept = tool.swept((0, 0), (10, 5), 0, 50)
        section = Part.Face(tool.profile(50, full=True)).Area
        union = swept.Solids[0].fuse(swept.Solids[1:])
        assert union.Volume == pytest.approx(s.Volume + math.hypot(10, 5) * section, rel=1e-6)


def test_checker_tool_solid_is_freecad_bit_solid(doc, tmp_path):
    """The tool solid the checker builds is FreeCAD's own bit solid (the shape
    file's) below the top of the flutes."""
    job = parts.make_job(doc, Part.makeBox(10, 10, 10))
    for kind, d, rc in (("flat", 12, 0), ("bull", 12, 2), ("ball", 8, 0)):
        tc = add_plungers(job, kind, [(d, rc)], str(tmp_path))[0]
        tool = ac.tool_of(tc)
        assert (tool.kind, tool.radius, tool.corner, tool.flute) == (kind, d / 2, rc if kind != "ball" else d / 2, 50)
        bit = tc.Tool.Shape.copy()
        bit.translate(V(0, 0, -bit.BoundBox.ZMin))
        mine = tool.solid(50)
        below = bit.common(Part.makeBox(100, 100, 50, V(-50, -50, 0)))
        assert below.Volume == pytest.approx(mine.Volume, rel=2e-3), kind
        assert below.common(mine).Volume == pytest.approx(mine.Volume, rel=2e-3), kind


def test_checker_reads_stops_from_path_commands():
    """Pecks, a raised lead-out and canned cycles, from the generator's commands."""
    from freecad_plugin import generator
    tool = ac.Tool("flat", 3)
    plunges = [{"x": 1, "y": 2, "z": -10, "approach_z": 1, "retract_z": 5, "pecks": [-4, -8]},
               {"x": 11, "y": 2, "z": -9, "approach_z": 1, "retract_z": 5, "lead_out": [11.5, 2],
                "lead_out_z": -8.8}]
    stops = ac.path_stops(generator.generate(plunges, 20, 10), tool)
    assert [(s.kind, s.x, s.y, s.z) for s in stops] == [("stop", 1, 2, -10), ("stop", 11, 2, -9),
                                                        ("lead-out", 11.5, 2, -8.8)]
    assert stops[2].start == (11, 2)
    canned = ac.path_stops(generator.generate([(1, 2, -10), (5, 6, -7)], 20, 10, canned_cycle=True), tool)
    assert [(s.x, s.y, s.z) for s in canned] == [(1, 2, -10), (5, 6, -7)]


def test_checker_finds_a_stop_too_low():
    """A flat tool stopping 0.2 above a floor fails, 0.3 above passes; 0.4 from a
    wall fails the radial allowance; a tip inside the part counts as 0."""
    part = Part.makeBox(100, 100, 40).cut(Part.makeBox(60, 60, 40, V(20, 20, 10)))
    tool = ac.Tool("flat", 5)
    good = ac.check(part, [ac.Stop(tool, 50, 50, 10.3)], RADIAL, FLOOR)
    assert good["failure_count"] == 0 and good["worst_floor"]["distance"] == pytest.approx(0.3, abs=1e-6)
    low = ac.check(part, [ac.Stop(tool, 50, 50, 10.2)], RADIAL, FLOOR)
    assert low["failure_count"] == 1 and low["failures"][0]["distance"] == pytest.approx(0.2, abs=1e-6)
    near = ac.check(part, [ac.Stop(tool, 25.4, 50, 10.3)], RADIAL, FLOOR)
    assert near["worst_radial"]["distance"] == pytest.approx(0.4, abs=1e-6) and near["failure_count"] == 1
    inside = ac.check(part, [ac.Stop(tool, 50, 50, 5)], RADIAL, FLOOR)
    assert inside["failure_count"] >= 1 and inside["failures"][0]["distance"] == 0
    # Beside a hole through the floor, 0.3 above it and 0.31 off its rim: the
    # hole's wall is all below the tool, which keeps the floor allowance from the rim.
    holed = part.cut(Part.makeCylinder(5, 40, V(50, 50, -5)))
    rim = ac.check(holed, [ac.Stop(tool, 50 + 5 + 5 + 0.31, 50, 10.3)], RADIAL, FLOOR)
    assert rim["failure_count"] == 0, rim["failures"]
    over = ac.measure_stop(ac.PartFaces(holed), ac.Stop(tool, 60.31, 50, 10.3), RADIAL, FLOOR)
    edge = [f for f in over if isinstance(holed.getElement(f["face"]).Surface, Part.Cylinder)]
    assert edge and edge[0]["contact"] == "over edge"
    assert edge[0]["distance"] == pytest.approx(math.hypot(0.31, 0.3), abs=1e-6)


# ---------------------------------------------------------------- the planner's stops

# Floor-stock plunges (Max Floor Stock 1 mm) on the smaller fillets; on the
# larger ones the floor-stock step alone plans hundreds of plunges on the fillets
# (minutes), so these keep the packing's and covering's stops only.
@pytest.mark.parametrize("radius,kind,floor_stock", [
    quick(1, "flat", 1.0), quick(3, "flat", 1.0, long=True), quick(5, "flat", 0.0, long=True),
    quick(10, "flat", 0.0, long=True), quick(1, "bull", 1.0), quick(5, "bull", 0.0, long=True),
    quick(3, "ball", 0.0), quick(10, "ball", 0.0, long=True)])
@pytest.mark.bundle
def test_filleted_pocket(doc, tmp_path, radius, kind, floor_stock):
    """60 x 40 pocket 20 deep, walls and floor edges filleted at one radius
    (spherical corners), placed off the origin and turned."""
    job, op, tcs = plan(doc, box_pocket(radius, radius), lowest_up_face, kind, tmp_path, placement=placed(),
                        MaxFloorStock=floor_stock)
    measured(job, op, "fillet_R%d_%s" % (radius, kind))


@full
@pytest.mark.parametrize("kind", ["flat", "bull", "ball"])
def test_corner_blends(doc, tmp_path, kind):
    """Walls filleted R5, then the floor edges R2: toroidal corner blends."""
    shape = box_pocket(5, 2, together=False)
    assert any(isinstance(f.Surface, Part.Toroid) for f in shape.Faces)
    job, op, tcs = plan(doc, shape, lowest_up_face, kind, tmp_path, placement=placed())
    measured(job, op, "blends_R5_R2_%s" % kind)


@full
def test_sculptured_example(doc, tmp_path):
    """The example part: a B-spline floor in a free-form pocket with an island,
    flat plungers (bull and ball ones take tens of minutes to measure)."""
    kind = "flat"
    job, op, tcs = plan(doc, parts.freeform_part(True), lambda s: [parts.floor_face_name(s, True)], kind, tmp_path,
                        tools=[(20, 0), (12, 0), (6, 0)])
    measured(job, op, "sculptured_%s" % kind)


def user_blends(doc, walls, floor, floor_end):
    """A block with a pocket (Part Cut of two Part Boxes) and a Part Fillet on the
    pocket's edges, as the Part workbench's dialog makes it: the vertical edges
    at `walls`, the floor's edges from `floor` to `floor_end` (a variable radius:
    B-spline fillets)."""
    block = doc.addObject("Part::Box", "Block")
    block.Length, block.Width, block.Height = 70, 50, 30
    cavity = doc.addObject("Part::Box", "PocketTool")
    cavity.Length, cavity.Width, cavity.Height = 50, 30, 30
    cavity.Placement.Base = V(10, 10, 12)
    cut = doc.addObject("Part::Cut", "Cut")
    cut.Base, cut.Tool = block, cavity
    doc.recompute()
    edges = []
    for i, e in enumerate(cut.Shape.Edges):
        b = e.BoundBox
        if not (9 < b.XMin and b.XMax < 61 and 9 < b.YMin and b.YMax < 41):
            continue
        if b.ZLength > 17 and b.XLength < 1e-6 and b.YLength < 1e-6:
            edges.append((i + 1, walls, walls))
        elif abs(b.ZMin - 12) < 1e-6 and abs(b.ZMax - 12) < 1e-6:
            edges.append((i + 1, floor, floor_end))
    assert len(edges) == 8
    fillet = doc.addObject("Part::Fillet", "Fillet")
    fillet.Base = cut
    fillet.Edges = edges
    cut.Visibility = False
    doc.recompute()
    assert fillet.Shape.isValid()
    return fillet


@pytest.mark.parametrize("walls,floor,floor_end,surface", [
    quick(0.5, 0.5, 0.5, Part.Sphere, long=True), quick(1, 1, 1, Part.Sphere, long=True),
    quick(3, 0.5, 0.5, Part.Toroid, long=True), quick(2, 0.5, 1.0, Part.BSplineSurface)])
@pytest.mark.bundle
def test_small_corner_blends(doc, tmp_path, walls, floor, floor_end, surface):
    """Small corner blends (R0.5 to R3: spherical, toroidal, B-spline) made with
    a Part Fillet as users do, planned with the fillets in the floor: they plan
    (the time is in the report) and keep the allowance in 3D."""
    part = user_blends(doc, walls, floor, floor_end)
    assert any(isinstance(f.Surface, surface) for f in part.Shape.Faces)
    job, op, tcs = plan(doc, part, lowest_up_face, "flat", tmp_path)
    assert op.IncludeFillets and "fillets added to the floor" in op.Summary
    measured(job, op, "blends_%g_%g_%g" % (walls, floor, floor_end))


def nist_part():
    if not os.path.exists(NIST_PART):
        pytest.skip("NIST part not found: %s (PLUNGE_NIST_PART)" % NIST_PART)
    shape = Part.read(NIST_PART)
    return shape.Solids[0] if len(shape.Solids) == 1 else shape


def test_nist_pocket_floors_found():
    floors = pocket_floors(nist_part())
    assert floors, "no pocket floor facing up"
    name, face, fillets = floors[0]
    assert fillets, "its largest pocket has no fillets"


@public_part
@pytest.mark.parametrize("kind", ["flat", "ball"])
def test_nist_filleted_pocket(doc, tmp_path, kind):
    """The NIST part's largest pocket facing up (its floor found on the part,
    R25 fillets and spherical corners to drafted walls, an opening through the
    floor), roughed with long plungers."""
    shape = nist_part()
    name, face, fillets = pocket_floors(shape)[0]
    depth = shape.BoundBox.ZMax - face.BoundBox.ZMin
    tools = [(25, 0), (16, 0), (10, 0)]
    job, op, tcs = plan(doc, shape, lambda s: [name], kind, tmp_path, tools=tools,
                        flute=math.ceil(depth + 20), length=math.ceil(depth + 60))
    # The fillets and corner blends added to the floor, not the rounds of the
    # drafted walls' corners above them (they rise the pocket's whole depth).
    added = re.search(r"fillets added to the floor: ([^;]+)", op.Summary).group(1).split(", ")
    model = job.Model.Group[0].Shape
    assert added and all(model.getElement(a.split(".")[-1]).BoundBox.ZMax < face.BoundBox.ZMin + 0.5 * depth
                         for a in added), added
    measured(job, op, "nist_%s_%s" % (name, kind))


# ---------------------------------------------------------------- the wall band above the floor

@pytest.mark.parametrize("walls,floor,together,include_fillets", [
    quick(3, 3, True, True, long=True), quick(3, 3, True, False), quick(5, 2, False, True, long=True),
    quick(5, 2, False, False, long=True), quick(10, 10, True, False, long=True)])
def test_wall_band_above_the_floor(doc, tmp_path, walls, floor, together, include_fillets):
    """The wall band (Max Wall Stock, 1 mm) measured from the part, corners
    included: at mid-wall height and just above the fillets and blends, where
    the walls stand vertical. What the plunges through a height cut there (each
    tool at its radius at that height, lead-outs aside) leaves nothing farther
    than the radial allowance and the band from the part's walls at that height,
    within 0.02 mm (0.01 of chords on the walls, 0.01 of measuring), on a grid
    of 0.05 mm. With the fillets as walls (not included) the pocket widens
    above its floor."""
    shape = box_pocket(walls, floor, together)
    job, op, tcs = plan(doc, shape, lowest_up_face, "flat", tmp_path, placement=placed(),
                        include_fillets=include_fillets)
    part = job.Model.Group[0].Shape
    stops = ac.job_stops(job, lead_outs=False)
    bottom = min(s.z for s in stops) - FLOOR  # the floor, as placed
    data = json.loads(op.PlanData)["input"]
    if not include_fillets:
        assert data.get("sections"), "the pocket widens above its floor: no section passed"
    band = op.MaxWallStock.Value
    above = bottom + max(walls, floor)  # the fillets' and blends' top: the walls stand vertical above
    for z in (above + 0.5, 0.5 * (above + part.BoundBox.ZMax)):
        left = ac.band_left(part, stops, z, RADIAL, band, tol=0.02)
        print("z %.2f: %s" % (z, left))
        assert left["core_points"] > 1000
        assert left["uncut"] <= 0.02, "at z = %.2f, uncut %.3f mm beyond the band at %s (%s)" % (
            z, left["uncut"], left["at"], op.Summary)
    # Within the fillets the walls lean in: just below each section the pocket
    # is nearly as wide as there, cut only by the plunges stopping lower. The
    # band said (at its worst height) is no thinner than the band sliced
    # there, and none is left thicker than the limit unsaid.
    said = [b for b in PlungeRough.plan_of(op).get("broken_limits", []) if b["limit"] == "max_wall_stock"]
    for s in data.get("sections", []):
        left = ac.band_left(part, stops, s["z"] - 0.02, RADIAL, band, tol=0.02)
        print("just below %.2f: %s" % (s["z"], left))
        worst = said[0]["worst"] if said else band
        assert left["thickest"] <= worst + 0.1, "just below z = %.2f, %.3f mm of band at %s, said %s (%s)" % (
            s["z"], left["thickest"], left["thickest_at"], worst, op.Summary)
