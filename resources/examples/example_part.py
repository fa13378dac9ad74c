"""The bundled example part (a mould cavity with a free-form wall, a free-form
island and a B-spline floor) and the Job helpers the demo and the tests share."""
import json
import math
import os
import tempfile

import FreeCAD
import Part

from freecad_plugin import PlungeRough
from freecad_plugin.compat import PathJob, PathToolController, tool_bit_from_file

V = FreeCAD.Vector


def closed_bspline(center, radius_fn, n=24, z=0.0):
    pts = []
    for k in range(n):
        t = 2 * math.pi * k / n
        r = radius_fn(t)
        pts.append(V(center[0] + r * math.cos(t), center[1] + r * math.sin(t), z))
    curve = Part.BSplineCurve()
    curve.interpolate(pts, PeriodicFlag=True)
    return Part.Wire([curve.toShape()])


def prism(wire, z0, height):
    face = Part.Face(wire)
    face.translate(V(0, 0, z0 - face.BoundBox.ZMin))
    return face.extrude(V(0, 0, height))


def freeform_part(sculptured=True):
    """The example: a 180 x 130 x 40 block with a free-form pocket, a free-form
    island and a sculptured (B-spline) or flat floor."""
    block = Part.makeBox(180, 130, 40)
    outer = closed_bspline((90, 65), lambda t: 58 + 9 * math.cos(2 * t) + 5 * math.sin(3 * t + 0.4), 28)
    island = closed_bspline((112, 60), lambda t: 13 + 4 * math.cos(2 * t + 0.5), 16)
    cavity = prism(outer, -5, 60)
    if sculptured:
        grid = []
        for i in range(13):
            row = []
            for j in range(10):
                x, y = -10 + 200 * i / 12, -10 + 150 * j / 9
                z = (14 + 3 * math.exp(-((x - 60) ** 2 + (y - 70) ** 2) / 500.0)
                     + 2 * math.exp(-((x - 120) ** 2 + (y - 40) ** 2) / 300.0) + 0.02 * x)
                row.append(V(x, y, z))
            grid.append(row)
        surface = Part.BSplineSurface()
        surface.interpolate(grid)
        above = surface.toShape().extrude(V(0, 0, 100))
        cavity = cavity.common(above)
    else:
        cavity = cavity.common(Part.makeBox(300, 300, 100, V(-50, -50, 15)))
    cavity = cavity.cut(prism(island, -5, 60))
    return block.cut(cavity).removeSplitter()


def deep_pocket_part(doc):
    """The second demo, where plunging pays: a die block 160 x 120 x 90 with a
    pocket 120 x 80 and 75 mm deep (3.75 x the 20 mm plunger), its vertical
    corners filleted at 12 mm, modelled as in the Part workbench: two boxes, a
    fillet on the pocket's vertical edges, a cut. Returns the cut."""
    block = doc.addObject("Part::Box", "DieBlock")
    block.Length, block.Width, block.Height = 160, 120, 90
    pocket = doc.addObject("Part::Box", "PocketVolume")
    pocket.Length, pocket.Width, pocket.Height = 120, 80, 80
    pocket.Placement.Base = V(20, 20, 15)
    doc.recompute()
    fillet = doc.addObject("Part::Fillet", "PocketCorners")
    fillet.Base = pocket
    fillet.Edges = [(i + 1, 12.0, 12.0) for i, e in enumerate(pocket.Shape.Edges)
                    if abs(e.BoundBox.XLength) < 1e-9 and abs(e.BoundBox.YLength) < 1e-9]
    cut = doc.addObject("Part::Cut", "DeepPocket")
    cut.Base, cut.Tool = block, fillet
    doc.recompute()
    return cut


def floor_face_name(shape, sculptured):
    """The pocket's floor: the B-spline face, or the lowest horizontal face inside the block."""
    best = None
    for i, f in enumerate(shape.Faces):
        name = "Face%d" % (i + 1)
        if sculptured:
            if isinstance(f.Surface, Part.BSplineSurface):
                return name
        elif isinstance(f.Surface, Part.Plane) and abs(abs(f.Surface.Axis.z) - 1) < 1e-9:
            z = f.BoundBox.ZMin
            if 0 < z < shape.BoundBox.ZMax - 1e-6 and (best is None or z < best[1]):
                best = (name, z)
    return best[0] if best else None


def make_job(doc, shape, name="Part"):
    part = doc.addObject("Part::Feature", name)
    part.Shape = shape
    doc.recompute()
    job = PathJob.Create("Job", [part])
    doc.recompute()
    return job


def write_tool_bit(diameter, folder):
    """A plunger's tool bit file (.fctb), as FreeCAD's tool library editor writes
    one per tool: FreeCAD builds the bit's solid (what the simulator cuts with)
    from these parameters. Setting Diameter on a bit made from another size's
    file would not rebuild that solid."""
    os.makedirs(folder, exist_ok=True)
    path = os.path.join(folder, "%gmm_Plunger.fctb" % diameter)
    bit = {"version": 2, "name": "%g mm plunger" % diameter, "shape": "endmill.fcstd", "shape-type": "Endmill",
           "parameter": {"Diameter": "%g mm" % diameter, "ShankDiameter": "%g mm" % diameter,
                         "CuttingEdgeHeight": "50 mm", "Length": "100 mm"},
           "attribute": {}}
    with open(path, "w") as f:
        json.dump(bit, f, indent=2)
    return path


def add_tool_controller(job, diameter, number, bit_folder=None):
    """A plunger tool controller from its own .fctb (in bit_folder, default a
    temporary folder), added to the job."""
    folder = bit_folder or os.path.join(tempfile.gettempdir(), "plungerough-bits")
    bit = tool_bit_from_file(write_tool_bit(diameter, folder), job.Document)
    tc = PathToolController.Create("TC: %g mm plunger" % diameter, tool=bit, toolNumber=number)
    tc.VertFeed = "150 mm/min"
    tc.HorizFeed = "600 mm/min"
    tc.SpindleSpeed = round(40000.0 / diameter)  # about 125 m/min cutting speed
    tc.SpindleDir = "Forward"
    job.Proxy.addToolController(tc)
    return tc


def add_plunge_rough(job, face, diameters=(20, 12, 6), bit_folder=None, **properties):
    """Plunger tool controllers (tool numbers from 2), then a Plunge Rough
    operation on the job's model face, as a user adds them; recomputed. The new
    operation ticks every plunger of the Job, the largest as its own."""
    doc = job.Document
    tcs = [add_tool_controller(job, d, i + 2, bit_folder) for i, d in enumerate(diameters)]
    op = PlungeRough.Create("PlungeRough", parentJob=job)
    clone = job.Model.Group[0]
    op.Base = [(clone, [face])]
    for name, value in properties.items():
        setattr(op, name, value)
    doc.recompute()
    return op, tcs
