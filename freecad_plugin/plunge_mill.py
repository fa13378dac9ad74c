"""A plunge-mill tool bit users can pick: its shape (a FreeCAD tool-bit shape
file), example bits and a tool library of them.

A plunge mill cuts with inserts on a ring at its bottom: it does not cut at its
centre, where a core of material stays inside each hole, and one plunge may cut
at most the inserts' width sideways. The shape carries both as parameters the
operation reads from the bit (tools.spec): CoreDiameter and
MaxEngagement (and MinEngagement, 0: none), next to the usual Diameter,
ShankDiameter, Length, CuttingEdgeHeight and Flutes (the inserts).

The shape is drawn to scale: the body, a recess where the core stays, and the
inserts' ring from the core to the diameter. It is made by this FreeCAD, as its
own shapes are (a PartDesign Body of a revolved sketch whose dimensions are
expressions of an "Attributes" property bag), so that each version reads a
file it wrote: the property bag's class lives in a different module in 0.20.

install() puts shape, bits and library where the running FreeCAD finds them:
  - up to 1.0, into the addon's Tools folder (Tools/Shape, Tools/Bit,
    Tools/Library): a bit file finds its shape in the Shape folder beside its
    own; the tool library editor opens Tools/Library, the Job's Add button
    takes a bit file;
  - in 1.1, also into the user's CAM asset library (shapes, bits and
    libraries are assets there): the bits appear in the Job's tool dialog and
    the library in the tool library editor.
"""
import json
import os

import FreeCAD

from freecad_plugin import compat

SHAPE = "plungemill"  # the shape's file name (plungemill.fcstd) and id
# The shape's picture with its parameters (the tool bit editor shows it in 1.1).
PICTURE = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "resources", "tools",
                       SHAPE + ".svg")
LABEL = "PlungeMill"  # the shape's Body label: FreeCAD 1.1 names the shape by it
LIBRARY = "PlungeMills"

# Shape parameters: (name, property type, tooltip).
PARAMETERS = [
    ("Diameter", "App::PropertyLength", "Cutting diameter"),
    ("ShankDiameter", "App::PropertyLength", "Shank diameter"),
    ("Length", "App::PropertyLength", "Overall tool length"),
    ("CuttingEdgeHeight", "App::PropertyLength", "Height of the body that may enter the hole"),
    ("Flutes", "App::PropertyInteger", "Number of inserts"),
    ("CoreDiameter", "App::PropertyLength", "Diameter of the core the inserts do not cut (it stays in the hole)"),
    ("MaxEngagement", "App::PropertyLength", "Widest radial band one plunge may cut (the inserts' cutting width)"),
    ("MinEngagement", "App::PropertyLength", "Narrowest band a plunge should cut (0: no limit)"),
]

# Example bits (indexable plunge mills): the inserts reach from the core to the
# diameter (CoreDiameter = Diameter - 2 MaxEngagement). The shank is narrower
# than the cutting diameter (the sketch has a shoulder between them).
BITS = [
    {"Diameter": 25, "ShankDiameter": 20, "Length": 150, "CuttingEdgeHeight": 80, "Flutes": 2,
     "CoreDiameter": 13, "MaxEngagement": 6, "MinEngagement": 0},
    {"Diameter": 32, "ShankDiameter": 25, "Length": 170, "CuttingEdgeHeight": 100, "Flutes": 3,
     "CoreDiameter": 16, "MaxEngagement": 8, "MinEngagement": 0},
]


def bit_name(p):
    return "%g mm plunge mill" % p["Diameter"]


def bit_file_name(p):
    return "%gmm_PlungeMill.fctb" % p["Diameter"]


def _property_bag_module():
    return compat.first_module("Path.Base.PropertyBag", "PathScripts.PathPropertyBag")


def make_shape(path):
    """Writes the plunge mill's shape file (FCStd) with this FreeCAD.

    Profile in the XZ plane, revolved about Z (the tool's axis, tip at the
    origin): the inserts' ring at z = 0 from the core to the diameter, the core
    recess above the core, the body up to the cutting edge height, the shank."""
    import Part
    import Sketcher
    active = FreeCAD.ActiveDocument
    doc = FreeCAD.newDocument("PlungeMillShape", hidden=True)
    try:
        body = doc.addObject("PartDesign::Body", "Body")
        body.Label = LABEL
        bag = _property_bag_module().Create("PropertyBag")
        bag.Label = "Attributes"
        defaults = BITS[0]
        for name, kind, tip in PARAMETERS:
            bag.Proxy.addCustomProperty(kind, name, "Shape", tip)
            setattr(bag, name, defaults[name])
        # In the Body's group, where FreeCAD's shapes keep it (Body.addObject
        # takes only PartDesign features).
        body.Group = body.Group + [bag]

        sketch = body.newObject("Sketcher::SketchObject", "Sketch")
        sketch.MapMode = "Deactivated"
        sketch.Placement = FreeCAD.Placement(FreeCAD.Vector(), FreeCAD.Rotation(FreeCAD.Vector(1, 0, 0), 90))
        d, ds, l, h = (defaults[k] for k in ("Diameter", "ShankDiameter", "Length", "CuttingEdgeHeight"))
        c = defaults["CoreDiameter"]
        recess = h / 4
        # Corners (r, z), counter-clockwise from the axis above the core.
        pts = [(0, recess), (c / 2, recess), (c / 2, 0), (d / 2, 0), (d / 2, h), (ds / 2, h), (ds / 2, l), (0, l)]
        V = FreeCAD.Vector
        for i in range(len(pts)):
            a, b = pts[i], pts[(i + 1) % len(pts)]
            sketch.addGeometry(Part.LineSegment(V(a[0], a[1], 0), V(b[0], b[1], 0)), False)
        n = len(pts)
        cons = []
        for i in range(n):
            cons.append(Sketcher.Constraint("Coincident", i, 2, (i + 1) % n, 1))
        for i in range(n):
            cons.append(Sketcher.Constraint("Horizontal" if i % 2 == 0 else "Vertical", i))
        cons.append(Sketcher.Constraint("PointOnObject", 0, 1, -2))  # on the axis
        cons.append(Sketcher.Constraint("PointOnObject", 2, 1, -1))  # the inserts' bottom at z = 0
        sketch.addConstraint(cons)
        # Dimensions bound to the attributes, as FreeCAD's own shapes do.
        dims = [
            (Sketcher.Constraint("DistanceX", -1, 1, 0, 2, c / 2), "<<Attributes>>.CoreDiameter / 2"),
            (Sketcher.Constraint("DistanceY", -1, 1, 0, 1, recess), "<<Attributes>>.CuttingEdgeHeight / 4"),
            (Sketcher.Constraint("DistanceX", -1, 1, 2, 2, d / 2), "<<Attributes>>.Diameter / 2"),
            (Sketcher.Constraint("DistanceY", -1, 1, 3, 2, h), "<<Attributes>>.CuttingEdgeHeight"),
            (Sketcher.Constraint("DistanceX", -1, 1, 4, 2, pts[5][0]), "<<Attributes>>.ShankDiameter / 2"),
            (Sketcher.Constraint("DistanceY", -1, 1, 5, 2, l), "<<Attributes>>.Length"),
        ]
        for con, expr in dims:
            index = sketch.addConstraint(con)
            sketch.setExpression("Constraints[%d]" % index, expr)

        rev = body.newObject("PartDesign::Revolution", "Revolution")
        rev.Profile = sketch
        rev.ReferenceAxis = (sketch, ["V_Axis"])
        rev.Angle = 360
        sketch.Visibility = False
        doc.recompute()
        if not rev.Shape.isValid() or rev.Shape.Volume <= 0:
            raise ValueError("the plunge mill's shape did not build")
        os.makedirs(os.path.dirname(path), exist_ok=True)
        doc.saveAs(path)
    finally:
        FreeCAD.closeDocument(doc.Name)
        if active is not None:
            FreeCAD.setActiveDocument(active.Name)
    return path


def bit_dict(p):
    """A bit's .fctb content: the shape's file and every parameter."""
    parameter = {name: "%g mm" % p[name] if kind == "App::PropertyLength" else p[name]
                 for name, kind, _ in PARAMETERS}
    return {"version": 2, "name": bit_name(p), "shape": SHAPE + ".fcstd", "parameter": parameter, "attribute": {}}


def ensure_installed(root=None):
    """The bits under the addon's Tools folder, made (and in 1.1 registered with
    the CAM asset library) the first time FreeCAD starts with an addon that has
    none: a git clone into Mod by the Addon Manager. Returns the bits made, or
    [] when they were there already."""
    root = root or os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    if os.path.isdir(os.path.join(root, "Tools", "Bit")):
        return []
    bits = install(root)
    FreeCAD.Console.PrintMessage("PlungeRough: the plunge-mill tool bits are in %s%s\n" % (
        os.path.join(root, "Tools"), " and the CAM asset library" if compat.tool_library() else ""))
    return bits


def install(root):
    """Shape, bits and library under root/Tools (Shape, Bit, Library); in 1.1
    also in the user's CAM asset library. Returns the bits' file paths."""
    import pathlib
    import shutil
    tools = os.path.join(root, "Tools")
    shape = make_shape(os.path.join(tools, "Shape", SHAPE + ".fcstd"))
    picture = shutil.copy(PICTURE, os.path.join(tools, "Shape", SHAPE + ".svg"))
    bits = []
    for p in BITS:
        path = os.path.join(tools, "Bit", bit_file_name(p))
        os.makedirs(os.path.dirname(path), exist_ok=True)
        with open(path, "w") as f:
            json.dump(bit_dict(p), f, indent=2)
        bits.append(path)
    library = os.path.join(tools, "Library", LIBRARY + ".fctl")
    os.makedirs(os.path.dirname(library), exist_ok=True)
    with open(library, "w") as f:
        json.dump({"version": 1, "label": "Plunge mills",
                   "tools": [{"nr": 90 + i, "path": os.path.basename(b)} for i, b in enumerate(bits)]}, f, indent=2)
    assets = compat.tool_library()
    if assets is not None:
        assets.add_file("toolbitshape", pathlib.Path(shape))
        assets.add_file("toolbitshapesvg", pathlib.Path(picture), asset_id=SHAPE + ".svg")
        for b in bits:
            assets.add_file("toolbit", pathlib.Path(b))
        assets.add_file("toolbitlibrary", pathlib.Path(library))
    return bits
