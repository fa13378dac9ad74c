"""Test parts built with Part booleans; the example part and Job helpers come from
resources/examples/example_part.py."""
import os
import sys

import FreeCAD
import Part

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))),
                                "resources", "examples"))
from example_part import (add_plunge_rough, add_tool_controller, closed_bspline, floor_face_name,  # noqa: E402,F401
                          freeform_part, make_job, prism)

V = FreeCAD.Vector


def islands_part():
    """A 160 x 100 x 30 block with a rectangular pocket 20 mm deep and two islands."""
    block = Part.makeBox(160, 100, 30)
    pocket = Part.makeBox(140, 80, 40, V(10, 10, 10))
    pocket = pocket.cut(Part.makeCylinder(12, 40, V(50, 50, 0)))
    pocket = pocket.cut(Part.makeBox(25, 30, 40, V(100, 30, 0)))
    return block.cut(pocket).removeSplitter()




def _at_floor(edge, z=15.0):
    b = edge.BoundBox
    return abs(b.ZMin - z) < 1e-6 and abs(b.ZMax - z) < 1e-6 and b.XMin > 1 and b.YMin > 1 and b.XMax < 319 \
        and b.YMax < 233


def tray():
    """A tray like NIST's: a 280 x 194 mm pocket 30 mm deep in a block, its
    walls rounded R12 and its floor edges filleted R6 (Part booleans and
    fillets, as a user models it)."""
    shape = Part.makeBox(320, 234, 45).cut(Part.makeBox(280, 194, 50, V(20, 20, 15))).removeSplitter()
    walls = [e for e in shape.Edges if e.BoundBox.ZLength > 29 and e.BoundBox.XLength < 1e-6
             and e.BoundBox.YLength < 1e-6 and 19 < e.BoundBox.XMin < 301 and 19 < e.BoundBox.YMin < 215]
    shape = shape.makeFillet(12, walls)
    shape = shape.makeFillet(6, [e for e in shape.Edges if _at_floor(e)])
    assert shape.isValid()
    return shape


def tray_floor(shape):
    """The tray's floor face's name."""
    return next("Face%d" % (i + 1) for i, f in enumerate(shape.Faces)
                if isinstance(f.Surface, Part.Plane) and abs(f.BoundBox.ZMax - 15) < 1e-6 and f.Area > 40000)
