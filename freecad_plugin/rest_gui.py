"""The rest material feature's view (GUI): its view provider, coloured by
height, and the GUI's way to make the feature and show it (rest.py is its App
side)."""
from PySide import QtCore

from freecad_plugin import rest


STOCK_COLOUR = (0.85, 0.55, 0.25)  # the rest material's top, apart from the part's grey
DEEPEST_COLOUR = (0.30, 0.45, 0.75)  # its lowest top


def depth_colours(shape):
    """A colour per face of a rest solid, by the height of the top of its box:
    stock colour at the highest, blue at the lowest (a face's top is its
    box's, but for the bottoms, shown as the lowest). FreeCAD's headlight
    shades the tops and sides of boxes alike in its isometric view: without
    colours the rest reads as one flat patch there."""
    boxes = [f.BoundBox for f in shape.Faces]
    sides = [b.ZMax for b in boxes if b.ZLength > 1e-6]
    if not sides:
        return [STOCK_COLOUR] * len(boxes)
    high, low = max(sides), min(sides)
    span = max(high - low, 1e-9)

    def mix(z):  # below the lowest side's top (the bottoms) as the lowest
        s = min(1.0, max(0.0, (high - z) / span))
        return tuple(a + (b - a) * s for a, b in zip(STOCK_COLOUR, DEEPEST_COLOUR))
    return [mix(b.ZMax) for b in boxes]


class ViewProviderRest:
    """The rest material's view provider: the shape shown as a Part's,
    coloured by height (depth_colours; a view provider without a proxy shows
    nothing)."""

    def __init__(self, vobj):
        vobj.Proxy = self

    def attach(self, vobj):
        self.Object = vobj.Object

    def updateData(self, obj, prop):
        # FreeCAD calls this before it rebuilds the shape's scene, and face
        # colours take only once the scene has the faces: so, just after.
        if prop == "Shape":
            QtCore.QTimer.singleShot(0, lambda: self.colour(obj))

    @staticmethod
    def colour(obj):
        try:
            if obj.ViewObject is not None and not obj.Shape.isNull():
                obj.ViewObject.DiffuseColor = depth_colours(obj.Shape)
        except ReferenceError:  # deleted before the scene was drawn
            pass

    def getDisplayModes(self, vobj):
        return ["Shaded", "Flat Lines", "Wireframe"]

    def getDefaultDisplayMode(self):
        return "Shaded"  # the edges of thousands of boxes would hide the steps in black

    def __getstate__(self):
        return None

    def __setstate__(self, state):
        return None

    dumps, loads = __getstate__, __setstate__


def make_and_show(op):
    """The operation's rest material feature (rest.make_rest_solid), shown with
    this view provider, in the stock colour until its faces are coloured by
    height."""
    def view(obj):
        ViewProviderRest(obj.ViewObject)
        obj.ViewObject.ShapeColor = STOCK_COLOUR
    return rest.make_rest_solid(op, view)
