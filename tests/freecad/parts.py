"""Test parts built with Part booleans; the example part and Job helpers come from
resources/examples/example_part.py."""
import os
import sys

import FreeCAD
import Part

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))),
                                "resources", "examples"))
from example_part import (add_plunge_rough, add_tool_controller, floor_face_name, freeform_part,  # noqa: E402,F401
                          make_job)

V = FreeCAD.Vector


def islands_part():
    """A 160 x 100 x 30 block with a rectangular pocket 20 mm deep and two islands."""
    block = Part.makeBox(160, 100, 30)
    pocket = Part.makeBox(140, 80, 40, V(10, 10, 10))
    pocket = pocket.cut(Part.makeCylinder(12, 40, V(50, 50, 0)))
    pocket = pocket.cut(Part.makeBox(25, 30, 40, V(100, 30, 0)))
    return block.cut(pocket).removeSplitter()


