"""From the floor face(s) a user selected to the planner's pocket description.

A pocket is what the selected faces bound together, with the part around them
(`pocket()`):
- the floor is every selected face plus, by default, the fillets that rise
  from it tangentially into the walls;
- its outline is the union of those faces in plan view, computed once on the
  exact curves (shared edges project onto the same curve, so faces that meet
  give one region without slivers), then discretised within the chord tolerance;
- each edge of the outline is a wall where the part rises next to it, or open
  where the part ends or steps down: an open hole is roughed to the floor's
  height, and past an open side the plunges may leave the pocket.
A planar, horizontal floor at one height is flat; any other floor goes to the
planner as BREP faces so that every plunge gets its own depth.
"""
import math
import os
import tempfile

import FreeCAD
import Part

from freecad_plugin import floor_mesh


class GeometryError(ValueError):
    """The selection cannot be planned; the message says why."""


# Points of a polyline closer than this (mm) are one: a section's wire may
# close, or join its edges, only within its tolerance.
SAME_POINT = 1e-6


def _xy(points):
    out = []
    for p in points:
        q = (round(p.x, 9), round(p.y, 9))
        if not out or math.hypot(out[-1][0] - q[0], out[-1][1] - q[1]) > SAME_POINT:
            out.append(q)
    if len(out) > 1 and math.hypot(out[0][0] - out[-1][0], out[0][1] - out[-1][1]) <= SAME_POINT:
        out.pop()
    return [list(q) for q in out]


def _edge_chords(edge, tolerance):
    """Points along the edge, in its parameter's direction, whose chords stay
    within `tolerance` of it, and the largest deviation measured: OCCT's
    deflection is not a strict bound, so each chord's midpoint is projected
    onto the curve, and the points are refined until within it."""
    curve = _curve_of(edge)
    if isinstance(curve, Part.Line):
        return [edge.valueAt(edge.FirstParameter), edge.valueAt(edge.LastParameter)], 0.0

    def off(m):  # the curve's distance from a chord's midpoint
        if curve is not None:
            return (curve.value(curve.parameter(m)) - m).Length
        return edge.distToShape(Part.Vertex(m))[0]
    deflection = tolerance
    for _ in range(6):
        points = edge.discretize(Deflection=deflection)
        deviation = 0.0
        for a, b in zip(points, points[1:]):
            if (a - b).Length > 1e-9:
                deviation = max(deviation, off((a + b) * 0.5))
        if deviation <= tolerance:
            break
        deflection *= 0.5
    return points, deviation


def _curve_of(edge):
    try:
        return edge.Curve
    except (Part.OCCError, TypeError, RuntimeError):  # a curve type FreeCAD does not wrap
        return None


def _off_wire(edges, m):
    """The distance from m to the nearest of the wire's edges: exact on a line,
    the curve's projection on any other (where FreeCAD wraps the curve)."""
    best = math.inf
    for e, curve, box in edges:
        if not (box.XMin <= m.x <= box.XMax and box.YMin <= m.y <= box.YMax and box.ZMin <= m.z <= box.ZMax):
            continue
        if isinstance(curve, Part.Line):
            a, b = e.Vertexes[0].Point, e.Vertexes[-1].Point
            ab = b - a
            t = max(0.0, min(1.0, (m - a).dot(ab) / max(ab.dot(ab), 1e-30)))
            d = (a + ab * t - m).Length
        elif curve is not None:
            d = (curve.value(curve.parameter(m)) - m).Length
        else:
            d = e.distToShape(Part.Vertex(m))[0]
        best = min(best, d)
    return best


def _chords(shape, tolerance):
    """Points along a wire or edge (OCCT's discretisation of the whole wire)
    whose chords stay within `tolerance` of it, and the largest deviation
    measured: OCCT's deflection is not a strict bound, so each chord's middle
    is measured against the edges near it (a line's distance, a curve's
    projection: no boolean distance per chord) and the points are refined
    until within it."""
    if shape.ShapeType == "Edge":
        return _edge_chords(shape, tolerance)
    edges = []
    for e in shape.Edges:
        box = e.BoundBox
        box.enlarge(tolerance * 4 + 1e-6)
        edges.append((e, _curve_of(e), box))
    deflection = tolerance
    for _ in range(6):
        points = shape.discretize(Deflection=deflection)
        deviation = 0.0
        for a, b in zip(points, points[1:]):
            if (a - b).Length > 1e-9:
                d = _off_wire(edges, (a + b) * 0.5)
                deviation = max(deviation, d if math.isfinite(d) else shape.distToShape(Part.Vertex((a + b) * 0.5))[0])
        if deviation <= tolerance:
            break
        deflection *= 0.5
    return points, deviation


def _polyline(wire, tolerance):
    """The wire as a closed XY polyline within `tolerance` of the curve, and the
    largest deviation measured."""
    points, deviation = _chords(wire, tolerance)
    return _xy(points), deviation


V = FreeCAD.Vector
# Fillets: the floor's and the fillet's normals agree within this along their edge.
TANGENT_COS = math.cos(math.radians(1.0))
# A face whose normal's z stays below this everywhere (steeper than 60 degrees)
# stands as a wall, drafted or not.
STEEP_Z = 0.5


def is_horizontal_plane(face):
    surface = face.Surface
    if not isinstance(surface, Part.Plane):
        return False
    return abs(abs(surface.Axis.z) - 1.0) < 1e-9


def _mesh(face):
    return face.tessellate(max(1e-3, 0.01 * face.BoundBox.DiagonalLength))


def _shadow_area(face, mesh=None):
    """Area of the face's shadow on the XY plane, from a tessellation (its
    `mesh` when already made): 0 for a wall."""
    points, triangles = mesh or _mesh(face)
    area = 0.0
    for a, b, c in triangles:
        p, q, r = points[a], points[b], points[c]
        area += abs((q.x - p.x) * (r.y - p.y) - (q.y - p.y) * (r.x - p.x)) / 2
    return area


def _normal(face, point):
    u, v = face.Surface.parameter(point)
    return face.normalAt(u, v)


def _check_face(name, face):
    if face.Area <= 1e-9:
        raise GeometryError("%s has no area: select the pocket's floor" % name)
    if _shadow_area(face) <= 1e-6 * max(face.Area, 1.0):
        raise GeometryError("%s is a wall (it stands vertical): select the pocket's floor instead, the face "
                            "the tool plunges onto" % name)


def _rises_from(floor, other, edge, corner=False):
    """`other` is a fillet of `floor` along `edge`: curved, tangent to the floor
    there, rising from the edge and facing up everywhere (into a wall above).
    corner: `floor` is itself a fillet, and `other` may be the blend between
    two fillets at a corner (as high as the fillet, not rising from the edge)."""
    if isinstance(other.Surface, Part.Plane) or _stands_vertical(other):
        return False  # a wall (a vertical edge's fillet stands, whatever trims its foot)
    if other.BoundBox.ZMax <= edge.BoundBox.ZMax + 1e-6 \
            and not (corner and other.BoundBox.ZMax <= floor.BoundBox.ZMax + 1e-6):
        return False
    mid = edge.valueAt(0.5 * (edge.FirstParameter + edge.LastParameter))
    try:
        if _normal(floor, mid).dot(_normal(other, mid)) < TANGENT_COS:
            return False
        mesh = _mesh(other)
        points = mesh[0]
        normals = [_normal(other, p).z for p in points[::max(1, len(points) // 64)]]
        if min(normals) < -1e-6:
            return False
        # Steep everywhere: a drafted wall, or the round of a drafted corner
        # rising from a corner blend, not a fillet (which leaves the floor
        # tangent, facing up): the pocket's walls are no floor to plunge on.
        if max(normals) < STEEP_Z:
            return False
    except (Part.OCCError, ValueError):
        return False
    return _shadow_area(other, mesh) > 1e-6 * max(other.Area, 1.0)


def _face_name(model, face):
    for i, f in enumerate(model.Faces):
        if f.isSame(face):
            return "Face%d" % (i + 1)
    return "a face"


def _fillets(model, faces):
    """The faces of the model that rise from the floor faces as fillets (and from
    those, as the corner patches between two fillets do)."""
    floor = list(faces)
    added = []
    queue = list(faces)
    while queue:
        face = queue.pop(0)
        corner = any(face.isSame(f) for f in added)
        for edge in face.Edges:
            for other in model.ancestorsOfType(edge, Part.Face):
                if any(other.isSame(f) for f in floor):
                    continue
                if _rises_from(face, other, edge, corner):
                    floor.append(other)
                    added.append(other)
                    queue.append(other)
    return added


class _Shadows:
    """Edges and faces projected onto z = 0, each edge once: an edge two faces
    share casts one shadow, so their shadows meet exactly."""

    def __init__(self, tolerance):
        self.tolerance = tolerance
        self.edges = {}
        self.deviation = 0.0  # largest distance of a chord from its curve

    def edge(self, e):
        for original, shadow in self.edges.get(e.hashCode(), []):
            if original.isSame(e):
                return shadow
        shadow = self._project(e)
        self.edges.setdefault(e.hashCode(), []).append((e, shadow))
        return shadow

    def _project(self, e):
        box = e.BoundBox
        if box.XLength < 1e-7 and box.YLength < 1e-7:
            return None  # vertical: no shadow
        ends = [V(v.Point.x, v.Point.y, 0) for v in e.Vertexes]
        if all(abs(v.Point.z - e.Vertexes[0].Point.z) < 1e-12 for v in e.Vertexes) and box.ZLength < 1e-7:
            shadow = e.copy()  # horizontal: the same curve, lowered (exact)
            shadow.translate(V(0, 0, -e.Vertexes[0].Point.z))
            return shadow
        if isinstance(e.Curve, Part.Line):
            return Part.makeLine(ends[0], ends[-1])
        # Any other curve: chords within the tolerance (measured in space, where
        # the curve is: its shadow is no farther). The chords are the shadow
        # both faces of the edge get, so the faces still meet exactly.
        spatial, deviation = _chords(e, self.tolerance)
        self.deviation = max(self.deviation, deviation)
        points = [V(p.x, p.y, 0) for p in spatial]
        # The chords run along the curve's parameter; a reversed edge lists its
        # vertices the other way round: each end snaps to its nearest vertex.
        points[0], points[-1] = (min(ends, key=lambda v: (v - p).Length) for p in (points[0], points[-1]))
        chord = ends[-1] - ends[0]
        if chord.Length > 1e-9 and all(abs(chord.cross(p - ends[0]).z) / chord.Length < 1e-7 for p in points):
            return Part.makeLine(ends[0], ends[-1])  # a curve in a vertical plane
        points = [p for i, p in enumerate(points) if i == 0 or (p - points[i - 1]).Length > 1e-9]
        return Part.makePolygon(points)

    def face(self, face):
        """The face's shadow: a planar face at z = 0 (seams and vertical edges drop out)."""
        edges = []
        for e in face.Edges:
            if e.isSeam(face):
                continue
            s = self.edge(e)
            if s is not None:
                edges.extend(s.Edges)
        faces = []
        for group in Part.sortEdges(edges):
            wire = Part.Wire(group)
            if wire.isClosed():
                faces.append(_upward(Part.Face(wire)))
        faces = sorted((f for f in faces if f.Area > 1e-12), key=lambda f: -f.Area)
        if not faces:
            return None
        return _upward(faces[0].cut(faces[1:]).Faces[0]) if len(faces) > 1 else faces[0]


class Pocket:
    """A pocket as the planner gets it: boundary and islands (XY polylines), the
    floor faces (selected and added fillets), flat caps over open holes and past
    open sides, and what the user should be told."""

    def __init__(self):
        self.boundary = []
        self.islands = []
        self.deviation = 0.0
        self.faces = []       # (name, face): the floor
        self.added = []       # names of the fillets added to the floor
        self.caps = []        # flat faces: open holes and the margin past open sides
        self.open_sides = 0   # runs of open edges on the outline
        self.holes = 0        # open holes roughed to the floor's height
        self.kept_walls = 0   # open sides kept as walls: part material within reach past them
        self.deeper = 0.0     # mm^2 of the cavity without a floor face under it, roughed at the floor's height
        self.lowest = 0.0     # lowest point of the floor
        self.tolerance = 0.01  # chord tolerance
        self.shadow = None    # the floor's outline in plan view, exact (a face at z = 0)

    def notes(self):
        """What the summary says of the pocket beyond the selection."""
        out = []
        if self.added:
            out.append("fillets added to the floor: %s" % ", ".join(self.added))
        if self.open_sides:
            out.append("%d open side%s: plunges reach past %s" % (self.open_sides, "s" if self.open_sides > 1 else "",
                                                                  "them" if self.open_sides > 1 else "it"))
        if self.holes:
            out.append("%d hole%s where the part goes deeper roughed at the floor's height"
                       % (self.holes, "s" if self.holes > 1 else ""))
        if self.deeper:
            out.append("the cavity around the floor planned whole: %.0f mm2 over a window or a deeper part roughed at "
                       "the floor's height" % self.deeper)
        if self.kept_walls:
            out.append("%d open side%s kept as walls (the part is within reach past them)"
                       % (self.kept_walls, "s" if self.kept_walls > 1 else ""))
        return out


def _rises_next_to(face, edge, step=0.05):
    """The face goes up from the edge, right next to it (a wall, a draft, a
    fillet), rather than down or level (the part ends or steps down there)."""
    for f in (0.25, 0.5, 0.75):
        t = edge.FirstParameter + f * (edge.LastParameter - edge.FirstParameter)
        m = edge.valueAt(t)
        try:
            away = _normal(face, m).cross(edge.tangentAt(t))
        except (Part.OCCError, ValueError):
            return face.BoundBox.ZMax > edge.BoundBox.ZMax + 1e-6
        if away.Length < 1e-12:
            continue
        away.normalize()
        for sign in (1, -1):
            u, v = face.Surface.parameter(m + away * (sign * step))
            if face.isPartOfDomain(u, v) and face.Surface.value(u, v).z - m.z > 1e-3 * step:
                return True
    return False


def _classify_edges(model, floor, shadows):
    """Shadows of the floor's edges on its outline: (walls, open). An edge is a
    wall where a face of the part next to it rises above it, open where the part
    ends or steps down."""
    walls, opened = [], []
    for face in floor:
        for e in face.Edges:
            others = [g for g in model.ancestorsOfType(e, Part.Face) if not any(g.isSame(f) for f in floor)]
            if not others and len(model.ancestorsOfType(e, Part.Face)) > 1:
                continue  # between two floor faces
            shadow = shadows.edge(e)
            if shadow is None:
                continue
            rises = any(_rises_next_to(g, e) for g in others)
            (walls if rises else opened).append((e, shadow))
    return walls, opened


def _segment_open(loop, walls, opened, tolerance):
    """For each segment of a polyline loop, whether it lies on an open edge."""
    if not opened:
        return [False] * len(loop)
    open_shadow = Part.makeCompound([s for _, s in opened])
    wall_shadow = Part.makeCompound([s for _, s in walls]) if walls else None
    out = []
    for i, a in enumerate(loop):
        b = loop[(i + 1) % len(loop)]
        m = Part.Vertex(V((a[0] + b[0]) / 2, (a[1] + b[1]) / 2, 0))
        d_open = open_shadow.distToShape(m)[0]
        d_wall = wall_shadow.distToShape(m)[0] if wall_shadow else math.inf
        out.append(d_open < d_wall and d_open <= tolerance + 1e-5)
    return out


def _outer_wire(face):
    """The face's outer boundary: the wire enclosing the most area. Not
    Face.OuterWire, which on a cut face can be an island's."""
    outer = face.OuterWire
    wires = face.Wires
    if len(wires) == 1:
        return outer
    largest = max(wires, key=lambda w: abs(Part.Face(w).Area))
    # OuterWire itself where it is the outer one: its start and direction are
    # the outline's first point and way round, which the plans start from.
    return outer if largest.isSame(outer) else largest


def _upward(face):
    """The face with its normal up: faces of one plane merge only when alike."""
    if face.normalAt(0, 0).z < 0:
        face.reverse()
    return face


def _polygon_face(loop):
    return _upward(Part.Face(Part.makePolygon([V(x, y, 0) for x, y in loop + [loop[0]]])))


def _air_above(model, face, z, top):
    """No part material over the flat face from z up to top."""
    if top <= z:
        return True
    prism = face.copy()
    prism.translate(V(0, 0, z))
    prism = prism.extrude(V(0, 0, top - z))
    return model.common(prism).Volume < 1e-6


def _signed_area(loop):
    return 0.5 * sum(a[0] * b[1] - b[0] * a[1] for a, b in zip(loop, loop[1:] + loop[:1]))


def _margin(loop, is_open, width):
    """The band past the open segments of a counter-clockwise loop: a rectangle
    past each, a disk at the vertices between two of them."""
    pieces = []
    n = len(loop)
    for i in range(n):
        if not is_open[i]:
            continue
        a, b = loop[i], loop[(i + 1) % n]
        dx, dy = b[0] - a[0], b[1] - a[1]
        length = math.hypot(dx, dy)
        if length < 1e-12:
            continue
        nx, ny = dy / length * width, -dx / length * width
        pieces.append(_polygon_face([a, b, [b[0] + nx, b[1] + ny], [a[0] + nx, a[1] + ny]]))
        if is_open[(i + 1) % n]:
            pieces.append(_upward(Part.Face(Part.Wire(Part.makeCircle(width, V(b[0], b[1], 0))))))
    return pieces


def pocket(selection, tolerance, include_fillets=True, margin=1.5, model=None):
    """The pocket the selected faces bound, with the part around them.

    selection: [(name, Part.Face)], model: the part's shape (walls, fillets and
    open edges are found on it; None: every edge is a wall), margin: how far
    plunges may reach past an open side, mm. GeometryError names a selection
    that is not one pocket's floor."""
    if not selection:
        raise GeometryError("select the pocket's floor face(s)")
    if tolerance <= 0:
        raise GeometryError("the chord tolerance must be greater than zero")
    for name, face in selection:
        _check_face(name, face)
    result = Pocket()
    result.tolerance = tolerance
    result.faces = list(selection)
    floor = [f for _, f in selection]
    if model is not None and include_fillets:
        for f in _fillets(model, floor):
            prefix = selection[0][0].rsplit(".", 1)[0]
            result.added.append("%s.%s" % (prefix, _face_name(model, f)))
            result.faces.append((result.added[-1], f))
            floor.append(f)
    shadows = _Shadows(tolerance)
    flats = [s for s in (shadows.face(f) for f in floor) if s is not None]
    if not flats:
        raise GeometryError("%s has no area under it: select the pocket's floor" % selection[0][0])
    union = flats[0].multiFuse(flats[1:]) if len(flats) > 1 else flats[0]
    union = union.removeSplitter()
    pieces = _pieces(union.Faces)
    walls, opened = _classify_edges(model, floor, shadows) if model is not None else ([], [])
    top = model.BoundBox.ZMax if model is not None else 0.0
    result.lowest = min(f.BoundBox.ZMin for f in floor)
    open_z = min([e.BoundBox.ZMin for e, _ in opened], default=result.lowest)
    result.deviation = shadows.deviation
    shadow = _one_face(pieces[0]) if len(pieces) == 1 else None
    is_open = []
    if shadow is not None:
        outer = _outer_wire(shadow)
        boundary, deviation = _polyline(outer, tolerance)
        result.deviation = max(result.deviation, deviation)
        if len(boundary) < 3 or abs(_signed_area(boundary)) < 1e-9:
            raise GeometryError("%s has no area under it: select the pocket's floor" % selection[0][0])
        if _signed_area(boundary) < 0:
            boundary.reverse()
        is_open = _segment_open(boundary, walls, opened, tolerance)
    # Floor faces apart, or an outline that steps down (a window, a trough
    # beside the floor): the pocket is the part's cavity around them, when it
    # is one, closed all round.
    if model is not None and (shadow is None or any(is_open)):
        cavity = _cavity(model, floor, union)
        if cavity is not None:
            return _cavity_pocket(result, cavity, union, open_z)
    if shadow is None:
        raise GeometryError("the selected faces (%s) make %d separate floors, not one pocket: select the floor "
                            "faces of one pocket (one operation per pocket)"
                            % (", ".join(n for n, _ in selection), len(pieces)))
    result.shadow = shadow
    for w in shadow.Wires:
        if w.isSame(outer):
            continue
        loop, deviation = _polyline(w, tolerance)
        result.deviation = max(result.deviation, deviation)
        if len(loop) < 3:
            continue
        hole = _polygon_face(loop)
        if all(_segment_open(loop, walls, opened, tolerance)) and _air_above(model, hole, open_z + 0.01, top):
            result.holes += 1  # the part goes deeper: roughed at the floor's height
            hole.translate(V(0, 0, open_z))
            result.caps.append(hole)
        else:
            result.islands.append(loop)
    if any(is_open):
        boundary = _open_sides(result, model, boundary, is_open, margin, open_z, top)
    result.boundary = boundary
    return result


def _pieces(faces):
    """The faces in groups that touch (a shadow split by the fuse is one piece)."""
    groups = []
    for f in faces:
        touching = [g for g in groups if any(f.distToShape(h)[0] < 1e-6 for h in g)]
        merged = [f] + [h for g in touching for h in g]
        groups = [g for g in groups if not any(g is t for t in touching)] + [merged]
    return groups


def _one_face(faces):
    """Touching faces of one plane as one face, or None where they stay apart."""
    if len(faces) == 1:
        return faces[0]
    fused = faces[0].fuse(faces[1:]).removeSplitter()
    return _upward(fused.Faces[0]) if len(fused.Faces) == 1 else None


def _cavity(model, floor, union):
    """The part's cavity the floor faces lie in, just above the highest of them
    (a face of the air there, closed all round), or None where they lie in no
    one closed cavity."""
    z = max(f.BoundBox.ZMax for f in floor) + 0.01
    points = [_face_point(f) for f in union.Faces]
    air = _air_at(model, z, points[0])
    if air is None:
        return None
    if not all(air.isInside(V(p.x, p.y, z), 1e-6, True) for p in points[1:]):
        return None
    return air


def _face_point(face):
    """A point of a flat face (its largest triangle's centre)."""
    points, triangles = face.tessellate(0.1)
    if not triangles:
        raise GeometryError("a selected face's outline does not close around an area (its edges cross): select the "
                            "pocket's floor faces again, or refine the part (Part > Refine shape)")
    a, b, c = max(triangles, key=lambda t: abs((points[t[1]] - points[t[0]]).cross(points[t[2]] - points[t[0]]).z))
    return (points[a] + points[b] + points[c]) * (1.0 / 3.0)


def _cavity_pocket(result, air, union, z):
    """The pocket as the part's cavity `air` (a face at some height): its
    outline and islands; what of it no floor face lies under (a window, a
    trough, the gap between two floor faces) is roughed at the floor's height z."""
    flat = air.copy()
    flat.translate(V(0, 0, -air.BoundBox.ZMin))
    outer = _outer_wire(flat)
    boundary, deviation = _polyline(outer, result.tolerance)
    if _signed_area(boundary) < 0:
        boundary.reverse()
    result.deviation = max(result.deviation, deviation)
    for w in flat.Wires:
        if w.isSame(outer):
            continue
        loop, deviation = _polyline(w, result.tolerance)
        result.deviation = max(result.deviation, deviation)
        if len(loop) >= 3:
            result.islands.append(loop)
    for f in flat.cut(union).Faces:
        if f.Area > 1e-6:
            cap = _upward(f)
            result.deeper += cap.Area
            cap.translate(V(0, 0, z))
            result.caps.append(cap)
    result.boundary = boundary
    result.shadow = flat
    return result


def _open_sides(result, model, boundary, is_open, margin, z, top):
    """The boundary grown by `margin` past its open segments, where the part
    leaves room (halved twice, then kept as a wall); the margin becomes a cap."""
    n = len(boundary)
    result.open_sides = sum(1 for i in range(n) if is_open[i] and not is_open[i - 1]) or 1
    region = _polygon_face(boundary)
    for width in (margin, margin / 2, margin / 4):
        grown = region.multiFuse(_margin(boundary, is_open, width)).removeSplitter()
        if len(grown.Faces) != 1:
            continue
        extra = grown.cut(region)
        if _air_above(model, extra, z + 0.01, top):
            loop, _ = _polyline(_outer_wire(grown.Faces[0]), result.tolerance)
            if _signed_area(loop) < 0:
                loop.reverse()
            for f in extra.Faces:
                f.translate(V(0, 0, z))
                result.caps.append(f)
            return loop
    result.kept_walls, result.open_sides = result.open_sides, 0
    return boundary


def floor_spec(pocket, final_depth, workdir=None, floors=("z", "brep")):
    """The planner's "floor": flat at final_depth when every floor face (and cap)
    is one horizontal plane, else the faces as a BREP file (written to workdir)
    for a planner that reads them (floors: the kinds it reads, planner.py),
    or as a mesh."""
    faces = [f for _, f in pocket.faces]
    if all(is_horizontal_plane(f) for f in faces):
        heights = {round(f.BoundBox.ZMin, 6) for f in faces + pocket.caps}
        if len(heights) == 1:
            return {"z": final_depth}
    if "brep" not in floors:
        return {"mesh": floor_mesh.floor_mesh(faces + pocket.caps)}
    compound = Part.makeCompound([f.copy() for f in faces + pocket.caps])
    if workdir is None:
        workdir = tempfile.mkdtemp(prefix="plungerough-")
    path = os.path.join(workdir, "floor.brep")
    compound.exportBrep(path)
    return {"brep": path}

def _stands(face):
    """The face stands upright everywhere: no shadow in plan view."""
    if _stands_vertical(face):
        return True
    if isinstance(face.Surface, (Part.Plane, Part.SurfaceOfExtrusion)):
        return False
    try:
        return _shadow_area(face) <= 1e-6 * max(face.Area, 1.0)
    except (Part.OCCError, ValueError):
        return False


def part_mesh(model, pocket, reach=1.0):
    """The planner's "part" (docs/plan-format.md): every face of the part but
    the floor's that comes within `reach` of the pocket's outline in plan view
    and above its lowest point, as triangles at the chord tolerance, each with
    its measured deviation. The planner keeps every stop off them (a tab or a
    dome over the floor, a neighbour's face), and takes what of them hangs
    over the floor out of the pocket. None without a part."""
    if model is None:
        return None
    xs = [p[0] for p in pocket.boundary]
    ys = [p[1] for p in pocket.boundary]
    top = model.BoundBox.ZMax
    box = FreeCAD.BoundBox(min(xs) - reach, min(ys) - reach, pocket.lowest - reach,
                           max(xs) + reach, max(ys) + reach, top + reach)
    floor = [f for _, f in pocket.faces]
    # Faces that stand (walls, plane or free-form) cast no shadow: the outline
    # keeps the plunges off them, and the faces at their top hold the tool up.
    faces = [f for f in model.Faces
             if f.BoundBox.intersect(box) and f.BoundBox.ZMax > pocket.lowest + 1e-6
             and not any(f.isSame(g) for g in floor) and not _stands(f)]
    if not faces:
        return None
    deflection = max(pocket.tolerance, 1e-3)
    vertices, triangles, deviations = [], [], []
    for face in faces:
        P, T, off = floor_mesh.face_mesh(face, deflection, math.inf)
        # The measure in the surface's parameters overstates the distance
        # where they crowd (a sphere's poles): there, the distance itself.
        for t in (i for i in range(len(T)) if off[i] > 4 * deflection):
            a, b, c = (FreeCAD.Vector(*P[k]) for k in T[t])
            off[t] = max(face.distToShape(Part.Vertex(p))[0] for p in ((a + b + c) / 3, (a + b) / 2, (b + c) / 2,
                                                                      (c + a) / 2))
        triangles.extend((T + len(vertices)).tolist())
        vertices.extend(P.tolist())
        # No less than the outline's own chords stray: where a face's edge is
        # the outline's (an island's top), the two must not be told apart.
        deviations.extend(max(d, pocket.deviation) for d in (off * floor_mesh.MARGIN).tolist())
    return {"vertices": vertices, "triangles": triangles, "deviation": deviations}


def distance(a, b):
    return math.hypot(a[0] - b[0], a[1] - b[1])


# ---------------------------------------------------------------- sections above the floor

MAX_SECTIONS = 10  # each costs one covering of the section: a few suffice where the pocket widens


def _stands_vertical(face):
    """A plane or cylinder standing upright: the pocket keeps its width along it."""
    s = face.Surface
    if isinstance(s, Part.Plane):
        return abs(s.Axis.z) < 1e-9
    if isinstance(s, Part.Cylinder):
        return abs(abs(s.Axis.z) - 1.0) < 1e-9
    if isinstance(s, Part.SurfaceOfExtrusion):  # a free-form wall drawn and extruded
        return abs(abs(s.Direction.z) - 1.0) < 1e-9
    return False


def _wall_faces(model, floor, lowest):
    """The faces of the part around the floor (its neighbours, and theirs: the
    corner blends between a wall's fillet and the floor's), within the pocket's height."""
    seen, ring, out = list(floor), list(floor), []
    for _ in range(2):
        nxt = []
        for face in ring:
            for edge in face.Edges:
                for other in model.ancestorsOfType(edge, Part.Face):
                    if any(other.isSame(f) for f in seen) or other.BoundBox.ZMin < lowest - 1e-6:
                        continue
                    seen.append(other)
                    nxt.append(other)
        out += nxt
        ring = nxt
    return out


def _section_heights(walls, lowest, top, band, part_top):
    """Where the pocket may widen above its floor: up each wall face that does
    not stand vertical (fillets, blends, drafts), at steps over which it widens
    about one band (at most four), to its top; the middle of the wall; the
    lowest first, at most MAX_SECTIONS spread over them."""
    heights = {0.5 * (lowest + top)}
    # The tops of islands and steps below the part's top: a section there is
    # taken just above (at their own height the cut would meet the face itself).
    tops = [f.BoundBox.ZMax for f in walls if is_horizontal_plane(f) and f.BoundBox.ZMax < part_top - 0.05]
    for f in walls:
        if _stands_vertical(f):
            continue
        lo, hi = max(f.BoundBox.ZMin, lowest), min(f.BoundBox.ZMax, top)
        widens = min(f.BoundBox.XLength, f.BoundBox.YLength)  # a fillet's radius, a draft's run
        n = max(1, min(4, int(math.ceil(widens / max(band, 0.1)))))
        heights.update(lo + (hi - lo) * k / n for k in range(1, n + 1))
    heights = {z + 0.02 if any(abs(z - t) < 0.01 for t in tops) else z for z in heights}
    picked = []
    for z in sorted(heights):
        if lowest + 0.05 < z < top - 0.05 and (not picked or z - picked[-1] > 0.25):
            picked.append(z)
    if len(picked) > MAX_SECTIONS:
        step = (len(picked) - 1) / (MAX_SECTIONS - 1)
        picked = [picked[round(k * step)] for k in range(MAX_SECTIONS)]
    return picked


def _inside_point(boundary, islands):
    """A point of the pocket's region (in neither an island nor outside): the
    middle of the widest span inside it along a few rows across the outline
    (even-odd crossings of the loops' edges), no boolean needed."""
    loops = [boundary] + list(islands)
    ys = [p[1] for p in boundary]
    best = None
    for k in range(1, 8):
        y = min(ys) + (max(ys) - min(ys)) * k / 8.0
        xs = sorted(a[0] + (y - a[1]) / (b[1] - a[1]) * (b[0] - a[0])
                    for loop in loops for a, b in zip(loop, loop[1:] + loop[:1]) if (a[1] <= y) != (b[1] <= y))
        for x0, x1 in zip(xs[::2], xs[1::2]):
            if best is None or x1 - x0 > best[0]:
                best = (x1 - x0, V(0.5 * (x0 + x1), y, 0))
    if best is None:
        raise GeometryError("the pocket's outline does not close around an area (its edges cross): select the "
                            "pocket's floor faces again, or refine the part (Part > Refine shape)")
    return best[1]


def _air_at(model, z, at):
    """The air of the part's cross-section at height z around the point `at`
    (a face: the pocket's outline there and its islands), None where the
    pocket opens to the outside at that height. From the part's section
    wires (a slice, much quicker than a boolean cut): the smallest loop
    around `at` is the pocket's, the loops inside it its islands."""
    p = V(at.x, at.y, z)
    try:
        loops = [Part.Face(w) for w in model.slice(V(0, 0, 1), z) if w.isClosed()]
        around = [f for f in loops if f.isInside(p, 1e-6, True)]
        if not around:
            return None
        outline = min(around, key=lambda f: f.Area)
        islands = [f for f in loops if f.Area < outline.Area and not f.isInside(p, 1e-6, True)
                   and outline.isInside(f.Vertexes[0].Point, 1e-6, True)]
        # Loops nested in an island (a hole in a boss) are the boss's, not the pocket's.
        islands = [f for f in islands if not any(g is not f and g.Area > f.Area
                                                 and g.isInside(f.Vertexes[0].Point, 1e-6, True) for g in islands)]
        if not islands:
            return outline
        # The outline with its islands as holes: a face made of its wires (no boolean).
        air = Part.makeFace([outline.OuterWire] + [f.OuterWire for f in islands], "Part::FaceMakerBullseye")
        return air.Faces[0] if air.Faces else None
    except (Part.OCCError, ValueError, IndexError):
        bb = model.BoundBox  # the section's loops do not close: the boolean way
        plane = Part.makePlane(bb.XLength + 20, bb.YLength + 20, V(bb.XMin - 10, bb.YMin - 10, z))
        for f in plane.cut(model).Faces:
            if f.isInside(p, 1e-6, True):
                fb = f.BoundBox
                if fb.XMin < bb.XMin - 5 or fb.YMin < bb.YMin - 5 or fb.XMax > bb.XMax + 5 or fb.YMax > bb.YMax + 5:
                    return None
                return f
        return None


def _air_within(model, z, outline, at):
    """The air of the part's cross-section at height z inside `outline` (a flat
    face at z = 0) around the point `at`, or None."""
    plane = outline.copy()
    plane.translate(V(0, 0, z))
    for f in plane.cut(model).Faces:
        if f.isInside(V(at.x, at.y, z), 1e-6, True):
            return f
    return None


def sections(model, pocket, top, band):
    """The pocket's cross-sections above its floor where it is wider there than
    its outline (fillets and corner blends left as walls, drafted walls): the
    planner keeps the wall band at each of their heights too. [{"z",
    "boundary", "islands"}], none without a part; and the largest deviation of
    their polylines from the part. A pocket open to a side is cut there by
    its own outline (its margin past the open sides included): islands that
    narrow upward (tapered bosses, sloped ribs) widen it there too."""
    if model is None:
        return [], 0.0
    floor = [f for _, f in pocket.faces]
    lowest = pocket.lowest
    at = _inside_point(pocket.boundary, pocket.islands)
    opened = pocket.open_sides or pocket.kept_walls
    outline = _polygon_face(pocket.boundary)
    out, deviation = [], 0.0
    below = outline.cut([_polygon_face(i) for i in pocket.islands]).Area if opened and pocket.islands \
        else outline.Area if opened else pocket.shadow.Area
    for z in _section_heights(_wall_faces(model, floor, lowest), lowest, top, band, model.BoundBox.ZMax):
        air = _air_within(model, z, outline, at) if opened else _air_at(model, z, at)
        if air is None or air.Area - below < 1e-3 * air.Length:
            continue  # open there, or no wider than the floor's outline or the section below
        below = air.Area
        loops = []
        outer = _outer_wire(air)
        for w in [outer] + [w for w in air.Wires if not w.isSame(outer)]:
            loop, d = _polyline(w, pocket.tolerance)
            deviation = max(deviation, d)
            loops.append(loop)
        if _signed_area(loops[0]) < 0:
            loops[0].reverse()
        out.append({"z": z, "boundary": loops[0], "islands": [i for i in loops[1:] if len(i) >= 3]})
    return out, deviation
