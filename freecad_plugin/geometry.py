"""From the floor face(s) a user selected to the planner's pocket description.

The outer wire of the floor is the pocket's wall, its inner wires are islands;
free-form edges are discretised within the chord tolerance. A planar,
horizontal floor is flat; any other floor goes to the planner as BREP faces so
that every plunge gets its own depth.
"""
import math
import os
import tempfile

import FreeCAD
import Part


class GeometryError(ValueError):
    """The selection cannot be planned; the message says why."""


def _xy(points):
    out = []
    for p in points:
        q = (round(p.x, 9), round(p.y, 9))
        if not out or out[-1] != q:
            out.append(q)
    if len(out) > 1 and out[0] == out[-1]:
        out.pop()
    return [list(q) for q in out]


def _polyline(wire, tolerance):
    """The wire as a closed XY polyline within `tolerance` of the curve, and the
    largest deviation measured (OCCT's deflection is not a strict bound: chord
    midpoints are checked and the polyline refined until they are within it)."""
    deflection = tolerance
    for _ in range(6):
        points = wire.discretize(Deflection=deflection)
        deviation = 0.0
        for a, b in zip(points, points[1:]):
            if (a - b).Length > 1e-9:
                deviation = max(deviation, wire.distToShape(Part.Vertex((a + b) * 0.5))[0])
        if deviation <= tolerance:
            break
        deflection *= 0.5
    return _xy(points), deviation


def _is_horizontal_plane(face):
    surface = face.Surface
    if not isinstance(surface, Part.Plane):
        return False
    n = surface.Axis
    return abs(abs(n.z) - 1.0) < 1e-9


def _check_face(name, face):
    if face.Area <= 1e-9:
        raise GeometryError("%s has no area" % name)
    # The face's shadow on the XY plane: a vertical face has none.
    box = face.BoundBox
    if box.XLength < 1e-6 or box.YLength < 1e-6:
        raise GeometryError("%s is vertical: select the pocket's floor, not a wall" % name)
    if isinstance(face.Surface, Part.Plane) and abs(face.Surface.Axis.z) < 1e-6:
        raise GeometryError("%s is vertical: select the pocket's floor, not a wall" % name)


def footprint(faces, tolerance):
    """The XY outline of the floor faces: (boundary, islands, deviation), the
    deviation being how far the polylines may stray from the true walls.

    faces: [(name, Part.Face)]. Several faces must form one connected floor.
    """
    if not faces:
        raise GeometryError("select the pocket's floor face(s)")
    if tolerance <= 0:
        raise GeometryError("the chord tolerance must be greater than zero")
    flat = []
    worst = 0.0
    for name, face in faces:
        _check_face(name, face)
        # Project onto z = 0: outer wire as a face with its holes.
        outer, deviation = _polyline(face.OuterWire, tolerance)
        worst = max(worst, deviation)
        if len(outer) < 3:
            raise GeometryError("%s has no area under it" % name)
        wires = [Part.makePolygon([FreeCAD.Vector(x, y, 0) for x, y in outer + [outer[0]]])]
        for w in face.Wires:
            if w.isSame(face.OuterWire):
                continue
            pts, deviation = _polyline(w, tolerance)
            worst = max(worst, deviation)
            if len(pts) >= 3:
                wires.append(Part.makePolygon([FreeCAD.Vector(x, y, 0) for x, y in pts + [pts[0]]]))
        try:
            flat.append(Part.Face(wires))
        except Part.OCCError:
            raise GeometryError("%s has no area under it" % name)
    shadow = flat[0]
    for f in flat[1:]:
        shadow = shadow.fuse(f)
    shadow = shadow.removeSplitter()
    if len(shadow.Faces) != 1:
        raise GeometryError("the selected faces do not form one connected floor; make one operation per pocket")
    floor = shadow.Faces[0]
    boundary = _xy(p for p in _vertices(floor.OuterWire))
    islands = []
    for w in floor.Wires:
        if not w.isSame(floor.OuterWire):
            islands.append(_xy(_vertices(w)))
    return boundary, islands, worst


def _vertices(wire):
    """The vertices of a polygonal wire in order."""
    return [v.Point for v in Part.Wire(Part.__sortEdges__(wire.Edges)).OrderedVertexes]


def floor_spec(faces, final_depth, workdir=None):
    """The planner's "floor": flat at final_depth for one horizontal plane,
    else the faces as a BREP file (written to workdir)."""
    if all(_is_horizontal_plane(f) for _, f in faces):
        heights = {round(f.BoundBox.ZMin, 6) for _, f in faces}
        if len(heights) == 1:
            return {"z": final_depth}
    compound = Part.makeCompound([f.copy() for _, f in faces])
    if workdir is None:
        workdir = tempfile.mkdtemp(prefix="plungerough-")
    path = os.path.join(workdir, "floor.brep")
    compound.exportBrep(path)
    return {"brep": path}


def bit_length(bit, name):
    """A length property of a tool bit in mm (None when the bit has none)."""
    value = getattr(bit, name, None)
    if value is None or isinstance(value, bool):
        return None
    return float(value.Value if hasattr(value, "Value") else value)


def tool_spec(tc, max_engagement=100.0, min_engagement=0.0):
    """A tool controller as a planner tool: diameter, number, shape, and what the
    bit says of it as a plunge mill: CuttingEdgeHeight (the flute length), and
    when present its own CoreDiameter (it does not cut at its centre; or
    CenterCutting false), MaxEngagement and MinEngagement properties. Without
    those, the operation's limits in % of the diameter (100 and 0: none)."""
    bit = tc.Tool
    diameter = float(bit.Diameter.Value if hasattr(bit.Diameter, "Value") else bit.Diameter)
    tool = {"diameter": diameter, "id": int(tc.ToolNumber)}
    feed = tc.VertFeed.getValueAs("mm/min").Value if hasattr(tc, "VertFeed") else 0.0
    if feed > 0:
        tool["feed"] = feed  # plunge feed, for the planner's time estimate
    shape = os.path.basename(str(getattr(bit, "BitShape", ""))).lower()
    if "ball" in shape:
        tool["shape"] = "ball"
    elif "bull" in shape:
        corner = None
        if hasattr(bit, "FlatRadius"):
            corner = diameter / 2 - float(bit.FlatRadius.Value)
        elif hasattr(bit, "CornerRadius"):
            corner = float(bit.CornerRadius.Value)
        if corner and 0 < corner <= diameter / 2:
            tool["shape"] = "bull"
            tool["corner_radius"] = corner
    flute = bit_length(bit, "CuttingEdgeHeight")
    if flute and flute > 0:
        tool["flute_length"] = flute
    core = bit_length(bit, "CoreDiameter")
    if getattr(bit, "CenterCutting", True) is False or (core and core > 0):
        if not core or core <= 0:
            raise ValueError("%s does not cut at its centre: give its bit a CoreDiameter" % tc.Label)
        tool["center_cutting"] = False
        tool["core_diameter"] = core
    if not 0 < max_engagement <= 100 or not 0 <= min_engagement < 100:
        raise ValueError("the engagement limits are percentages: max above 0 and up to 100, min from 0 below 100")
    limit = bit_length(bit, "MaxEngagement")
    if limit is None and max_engagement < 100:
        limit = diameter * max_engagement / 100.0
    if limit:
        tool["max_engagement"] = limit
    least = bit_length(bit, "MinEngagement")
    if least is None and min_engagement > 0:
        least = diameter * min_engagement / 100.0
    if least:
        tool["min_engagement"] = least
    return tool


def distance(a, b):
    return math.hypot(a[0] - b[0], a[1] - b[1])
