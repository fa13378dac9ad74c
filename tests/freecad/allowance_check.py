"""An independent 3D allowance check of Plunge Rough stops, with OpenCASCADE.

The requirement: at every stop, the tool's solid keeps at least the floor
allowance from the part's faces, and at least the radial allowance from the
vertical walls. Measured here with BRepExtrema (Part's distToShape) between the
tool's solid at the stop and each face of the part's solid, the model the Job
machines; it passes at >= allowance - TOL.

- The tool solid: flat, bull (corner radius) or ball, revolved from its profile,
  from the tip up to the top of its flutes (CuttingEdgeHeight), or to above the
  part's top when the bit has no flute length.
- The stops come from the posted Path commands of the operations (the Job's
  coordinates, the same as the model's): the deepest point of each feed down at
  one X Y (pecks included; G81/G82/G83 at their Z). The lead-out feeds at depth
  can be checked too (the tool swept along them), reported apart.
- A vertical face (its normal has no Z component anywhere) needs the radial
  allowance where the tool is beside it; where the tool is above its top edge
  (the rim of a hole or step down in the floor: the closest points more
  vertical than horizontal apart) it needs the floor allowance, as the floor
  face sharing that edge does. Every other face needs the floor allowance.
- A tool whose tip lies inside the part's material counts as distance 0.

Nothing here comes from the planner or the operation's own geometry code: only
the part's faces, the tool bit's parameters and the Path commands.
"""
import math
import time

import FreeCAD
import numpy as np
import Part

from freecad_plugin import compat

V = FreeCAD.Vector
TOL = 0.005
MARGIN = 1.0  # faces farther (by bounding box) than allowance + MARGIN are not measured
VERTICAL_NZ = 1e-6


# ---------------------------------------------------------------- tools

class Tool:
    """A plunger's cutting part: kind "flat", "bull" or "ball", radius, corner
    radius (0 flat, radius for ball), flute length (None: unlimited)."""

    def __init__(self, kind, radius, corner=0.0, flute=None, label=""):
        if kind == "ball":
            corner = radius
        elif kind == "flat":
            corner = 0.0
        if not 0 <= corner <= radius + 1e-9:
            raise ValueError("corner radius %g outside [0, %g]" % (corner, radius))
        self.kind, self.radius, self.corner, self.flute, self.label = kind, radius, corner, flute, label
        self._solids = {}

    def key(self):
        return (self.kind, round(self.radius, 6), round(self.corner, 6), self.flute)

    def __repr__(self):
        return "%s D%g%s" % (self.kind, 2 * self.radius, " rc%g" % self.corner if self.kind == "bull" else "")

    def profile(self, height, full=False):
        """The outline in the XZ plane (tip at the origin) as a closed wire: the
        right half and the axis, or with full both halves (for sweeps)."""
        r, rc = self.radius, self.corner
        c45 = math.sqrt(0.5)
        flat = r - rc > 1e-9

        def seg(a, b):
            return Part.LineSegment(V(*a), V(*b)).toShape()

        def corner(sign):  # from the bottom up, on the side of sign
            return Part.Arc(V(sign * (r - rc), 0, 0), V(sign * (r - rc + rc * c45), 0, rc - rc * c45),
                            V(sign * r, 0, rc)).toShape()

        edges = []
        if not full:
            if flat:
                edges.append(seg((0, 0, 0), (r - rc, 0, 0)))
            if rc > 1e-9:
                edges.append(corner(1))
            edges += [seg((r, 0, rc), (r, 0, height)), seg((r, 0, height), (0, 0, height)),
                      seg((0, 0, height), (0, 0, 0))]
            return Part.Wire(edges)
        if rc > 1e-9:
            edges.append(corner(-1).reversed())
        if flat:
            edges.append(seg((-(r - rc), 0, 0), (r - rc, 0, 0)))
        if rc > 1e-9:
            edges.append(corner(1))
        edges += [seg((r, 0, rc), (r, 0, height)), seg((r, 0, height), (-r, 0, height)),
                  seg((-r, 0, height), (-r, 0, rc))]
        return Part.Wire(Part.__sortEdges__(edges))

    def solid(self, height):
        """The tool's solid, tip at the origin, `height` tall (cached)."""
        key = round(height, 6)
        if key not in self._solids:
            face = Part.Face(self.profile(height))
            s = face.revolve(V(0, 0, 0), V(0, 0, 1), 360)
            if s.ShapeType != "Solid":
                s = Part.Solid(Part.Shell(s.Faces))
            if s.Volume < 0:
                s.reverse()
            self._solids[key] = s
        return self._solids[key]

    def at(self, x, y, z, height):
        s = self.solid(height).copy()
        s.translate(V(x, y, z))
        return s

    def swept(self, a, b, z, height):
        """The tool fed horizontally from (a, z) to (b, z): both ends and the prism
        of its axial section across the move, whose union is the swept volume
        (exact for a tool of revolution, which is convex)."""
        ends = [self.at(a[0], a[1], z, height), self.at(b[0], b[1], z, height)]
        dx, dy = b[0] - a[0], b[1] - a[1]
        length = math.hypot(dx, dy)
        if length < 1e-9:
            return ends[0]
        section = Part.Face(self.profile(height, full=True))
        # The XZ section turned so that its X runs across the move (the move along +Y).
        section.rotate(V(0, 0, 0), V(0, 0, 1), math.degrees(math.atan2(dy, dx)) - 90.0)
        section.translate(V(a[0], a[1], z))
        prism = section.extrude(V(dx, dy, 0))
        # A compound, not fused: the distance to it is the nearest of the three
        # (fusing them costs ten times the measuring).
        return Part.makeCompound(ends + [prism])


def _mm(value):
    if value is None or isinstance(value, bool):
        return None
    return float(value.Value if hasattr(value, "Value") else value)


def tool_of(tc):
    """The Tool of a tool controller, from its bit's own parameters."""
    bit = tc.Tool
    radius = _mm(bit.Diameter) / 2
    shape = compat.bit_shape(bit)  # the addon's reading of FreeCAD's bits
    flute = _mm(getattr(bit, "CuttingEdgeHeight", None))
    flute = flute if flute and flute > 0 else None
    if "ball" in shape:
        return Tool("ball", radius, flute=flute, label=tc.Label)
    if "bull" in shape:
        if hasattr(bit, "CornerRadius"):
            corner = _mm(bit.CornerRadius)
        else:
            corner = radius - _mm(bit.FlatRadius)
        return Tool("bull", radius, corner, flute=flute, label=tc.Label)
    return Tool("flat", radius, flute=flute, label=tc.Label)


# ---------------------------------------------------------------- stops

class Stop:
    """A place the tool reaches: kind "stop" (the bottom of a plunge) or
    "lead-out" (a horizontal feed at depth from a to (x, y))."""

    def __init__(self, tool, x, y, z, op="", kind="stop", start=None):
        self.tool, self.x, self.y, self.z, self.op, self.kind, self.start = tool, x, y, z, op, kind, start

    def key(self):
        k = (self.tool.key(), self.kind, round(self.x, 5), round(self.y, 5), round(self.z, 5))
        return k + ((round(self.start[0], 5), round(self.start[1], 5)) if self.start else ())

    def as_dict(self):
        d = {"tool": repr(self.tool), "tc": self.tool.label, "op": self.op, "kind": self.kind,
             "x": round(self.x, 4), "y": round(self.y, 4), "z": round(self.z, 4)}
        if self.start:
            d["from"] = (round(self.start[0], 4), round(self.start[1], 4))
        return d


def path_stops(commands, tool, op_label="", placement=None, lead_outs=True):
    """The stops of one tool's Path commands: the deepest point of each run of
    feeds down at one X Y (G1 Z moves; pecks in between rapid up and down again at
    that X Y), each canned cycle's Z, and, with lead_outs, each horizontal feed
    made below the start of its plunge (a lead-out)."""
    x = y = z = None
    stops = []
    motion = None
    run = None  # the plunge being fed: (x, y, lowest z, z where it started)
    for c in commands:
        name = c.Name.upper()
        if name.startswith("("):
            continue
        p = {k.upper(): v for k, v in c.Parameters.items()}
        if name in ("G0", "G00", "G1", "G01", "G81", "G82", "G83"):
            motion = name.replace("G00", "G0").replace("G01", "G1")
        if name == "G80":
            motion = None
        if not any(k in p for k in "XYZ"):
            continue
        nx, ny, nz = p.get("X", x), p.get("Y", y), p.get("Z", z)
        moved_xy = x is not None and (abs(nx - x) > 1e-9 or abs(ny - y) > 1e-9)
        if motion in ("G81", "G82", "G83"):
            stops.append(Stop(tool, nx, ny, nz, op_label))
            r = p.get("R", z)
            x, y, z = nx, ny, max(r, z if z is not None else r)
            run = None
            continue
        if moved_xy and run is not None:
            stops.append(Stop(tool, run[0], run[1], run[2], op_label))
            if motion == "G1" and lead_outs and abs(nz - z) < 1e-9:
                stops.append(Stop(tool, nx, ny, nz, op_label, "lead-out", start=(x, y)))
            run = None
        elif motion == "G1" and lead_outs and moved_xy and abs(nz - z) < 1e-9 and z is not None:
            stops.append(Stop(tool, nx, ny, nz, op_label, "lead-out", start=(x, y)))
        if motion == "G1" and not moved_xy and z is not None and nz < z - 1e-9:
            if run is None:
                run = [nx, ny, nz]
            else:
                run[2] = min(run[2], nz)
        x, y, z = nx, ny, nz
    if run is not None:
        stops.append(Stop(tool, run[0], run[1], run[2], op_label))
    if placement is not None and not placement.isIdentity():
        for s in stops:
            p = placement.multVec(V(s.x, s.y, s.z))
            s.x, s.y, s.z = p.x, p.y, p.z
            if s.start:
                q = placement.multVec(V(s.start[0], s.start[1], s.z))
                s.start = (q.x, q.y)
    return stops


def job_stops(job, ops=None, lead_outs=True):
    """The stops of the Job's active operations (or of ops), each with its tool
    controller's tool, from their Path commands."""
    out = []
    tools = {}
    for op in (ops if ops is not None else job.Operations.Group):
        if not getattr(op, "Active", True) or not hasattr(op, "Path") or op.ToolController is None:
            continue
        tc = op.ToolController
        if tc.Name not in tools:
            tools[tc.Name] = tool_of(tc)
        out += path_stops(op.Path.Commands, tools[tc.Name], op.Label, getattr(op, "Placement", None), lead_outs)
    return out


# ---------------------------------------------------------------- faces

def is_vertical(face, samples=9):
    """The face's normal has no Z component anywhere (sampled over its
    parameter range; planes and cylinders exactly)."""
    s = face.Surface
    if isinstance(s, Part.Plane):
        return abs(s.Axis.z) < VERTICAL_NZ
    if isinstance(s, Part.Cylinder):
        return abs(abs(s.Axis.z) - 1) < VERTICAL_NZ
    if isinstance(s, (Part.Sphere, Part.Toroid, Part.Cone)):
        return False
    u0, u1, v0, v1 = face.ParameterRange
    for i in range(samples):
        for j in range(samples):
            u = u0 + (u1 - u0) * i / (samples - 1)
            v = v0 + (v1 - v0) * j / (samples - 1)
            try:
                n = face.normalAt(u, v)
            except Part.OCCError:
                continue
            if abs(n.z) > VERTICAL_NZ:
                return False
    return True


class PartFaces:
    """The part's faces, classified once: (name, face, vertical, bound box)."""

    def __init__(self, part):
        self.part = part
        self.solid = part.Solids[0] if part.Solids else part
        self.top = part.BoundBox.ZMax
        self.faces = []
        for i, f in enumerate(part.Faces):
            self.faces.append(("Face%d" % (i + 1), f, is_vertical(f), f.BoundBox))

    def slope(self, name, point):
        """Degrees between the face's normal at the point and +Z (0: a floor
        facing up, 90: a wall), with its surface type."""
        face = self.part.getElement(name)
        try:
            u, v = face.Surface.parameter(point)
            n = face.normalAt(u, v)
            return round(math.degrees(math.acos(max(-1.0, min(1.0, n.z)))), 1), type(face.Surface).__name__
        except Part.OCCError:
            return None, type(face.Surface).__name__


def _box_gap(a, b):
    dx = max(0.0, a.XMin - b.XMax, b.XMin - a.XMax)
    dy = max(0.0, a.YMin - b.YMax, b.YMin - a.YMax)
    dz = max(0.0, a.ZMin - b.ZMax, b.ZMin - a.ZMax)
    return math.sqrt(dx * dx + dy * dy + dz * dz)


# ---------------------------------------------------------------- the check

def tool_height(tool, z, top):
    """The solid's height: the flute length, else up to 1 mm above the part's top."""
    return tool.flute if tool.flute else max(top - z + 1.0, 2 * tool.radius)


def measure_stop(pf, stop, radial, floor, margin=MARGIN):
    """The findings of one stop: a dict per measured face (distance, need,
    points), nearest first, and whether the tool's tip is inside the material."""
    tool = stop.tool
    height = tool_height(tool, stop.z, pf.top)
    if stop.kind == "lead-out":
        solid = tool.swept(stop.start, (stop.x, stop.y), stop.z, height)
    else:
        solid = tool.at(stop.x, stop.y, stop.z, height)
    box = solid.BoundBox
    found = []
    for name, face, vertical, fbox in pf.faces:
        need = radial if vertical else floor
        if _box_gap(box, fbox) > max(radial, floor) + margin:
            continue
        d, pairs, _ = solid.distToShape(face)
        q, p = pairs[0]  # on the tool, on the part
        contact = "beside"
        if vertical:
            u = q - p
            # Above a step down's rim (or a hole's in the floor): the wall is all
            # below the tool, which keeps the floor allowance from the rim.
            if d > 1e-9 and (abs(u.z) > math.hypot(u.x, u.y) or (p.z >= fbox.ZMax - 1e-6 and u.z > 1e-6)):
                contact, need = "over edge", floor
        found.append({"face": name, "vertical": vertical, "contact": contact, "distance": d, "need": need,
                      "point": (round(p.x, 3), round(p.y, 3), round(p.z, 3)),
                      "tool_point": (round(q.x, 3), round(q.y, 3), round(q.z, 3))})
    tip = V(stop.x, stop.y, stop.z + 1e-3)
    if pf.solid.isInside(tip, 1e-6, False):
        found.append({"face": "(tip inside the part)", "vertical": False, "contact": "inside", "distance": 0.0,
                      "need": floor, "point": (round(tip.x, 3), round(tip.y, 3), round(tip.z, 3)),
                      "tool_point": (round(tip.x, 3), round(tip.y, 3), round(tip.z, 3))})
    found.sort(key=lambda f: f["distance"] - f["need"])
    return found


def check(part, stops, radial, floor, tol=TOL, margin=MARGIN, keep=10):
    """Measures every distinct stop (tool, x, y, z; lead-outs apart) against the
    part's faces. The report:
      stops / lead_outs: how many distinct ones were measured;
      worst_floor / worst_radial: the nearest non-vertical face and vertical
        face (beside it) over all stops, with the stop, face, distance, point,
        slope of the face there (degrees from up) and its surface type;
      failures: findings below need - tol, worst first (at most `keep` per kind
        of stop, and count in failure_count / failing_stops);
      lead_out_failures, worst_lead_out: the same for the lead-out feeds;
      by_face: the nearest distance per face;
      seconds."""
    t0 = time.time()
    pf = part if isinstance(part, PartFaces) else PartFaces(part)
    seen = set()
    worst = {"floor": None, "radial": None, "lead-out": None}
    fails = {"stop": [], "lead-out": []}
    failing = {"stop": set(), "lead-out": set()}
    by_face = {}
    counts = {"stop": 0, "lead-out": 0}
    for s in stops:
        k = s.key()
        if k in seen:
            continue
        seen.add(k)
        counts[s.kind] += 1
        for f in measure_stop(pf, s, radial, floor, margin):
            rec = dict(f, stop=s.as_dict(), distance=round(f["distance"], 4))
            if f["face"].startswith("Face"):
                rec["slope"], rec["surface"] = pf.slope(f["face"], V(*f["point"]))
            kind = "radial" if f["vertical"] and f["contact"] == "beside" else "floor"
            slot = "lead-out" if s.kind == "lead-out" else kind
            if worst[slot] is None or f["distance"] - f["need"] < worst[slot]["distance"] - worst[slot]["need"]:
                worst[slot] = rec
            if s.kind == "stop":
                prev = by_face.get(f["face"])
                if prev is None or f["distance"] < prev["distance"]:
                    by_face[f["face"]] = {"distance": round(f["distance"], 4), "need": f["need"],
                                          "surface": rec.get("surface"), "vertical": f["vertical"]}
            if f["distance"] < f["need"] - tol:
                fails[s.kind].append(rec)
                failing[s.kind].add(k)
    for kind in fails:
        fails[kind].sort(key=lambda r: r["distance"] - r["need"])
    return {"stops": counts["stop"], "lead_outs": counts["lead-out"],
            "worst_floor": worst["floor"], "worst_radial": worst["radial"], "worst_lead_out": worst["lead-out"],
            "failure_count": len(fails["stop"]), "failing_stops": len(failing["stop"]),
            "failures": fails["stop"][:keep],
            "lead_out_failure_count": len(fails["lead-out"]), "lead_out_failures": fails["lead-out"][:keep],
            "by_face": by_face, "seconds": round(time.time() - t0, 2), "tol": tol,
            "allowance": {"radial": radial, "floor": floor}}


def check_job(job, radial, floor, ops=None, lead_outs=True, **kw):
    """check() of the Job's operations' stops against the Job's model (its first
    model object's shape, placed as the Job machines it)."""
    part = job.Model.Group[0].Shape
    return check(part, job_stops(job, ops, lead_outs), radial, floor, **kw)


# ---------------------------------------------------------------- the wall band at a height

def radius_at(tool, bottom, z):
    """The radius the tool cuts at height z with its tip at `bottom` (0 below the tip)."""
    h = z - bottom
    if h <= 0:
        return 0.0
    if h >= tool.corner:
        return tool.radius
    rc = tool.corner
    return tool.radius - rc + math.sqrt(max(0.0, rc * rc - (rc - h) ** 2))


def air_at(part, z, inside):
    """The part's cross-section of air at height z around the point `inside`
    (x, y): a face whose outer wire is the pocket's wall there."""
    bb = part.BoundBox
    plane = Part.makePlane(bb.XLength + 20, bb.YLength + 20, V(bb.XMin - 10, bb.YMin - 10, z))
    for f in plane.cut(part).Faces:
        if f.isInside(V(inside[0], inside[1], z), 1e-6, True):
            return f
    raise ValueError("no air at z = %g around %s" % (z, inside))


def _loops(face):
    """The face's wires as closed XY polylines within 5 um (numpy arrays)."""
    out = []
    for w in face.Wires:
        pts = w.discretize(Deflection=0.005)
        out.append(np.array([(p.x, p.y) for p in pts]))
    return out


def _inside_and_wall(points, loops):
    """Even-odd inside test of the points against the loops, and each point's
    distance to the nearest segment of them."""
    inside = np.zeros(len(points), dtype=bool)
    wall = np.full(len(points), np.inf)
    x, y = points[:, 0:1], points[:, 1:2]
    for L in loops:
        a, b = L[:-1], L[1:]
        ax, ay, bx, by = a[:, 0], a[:, 1], b[:, 0], b[:, 1]
        crosses = ((ay > y) != (by > y)) & (x < (bx - ax) * (y - ay) / np.where(by == ay, 1e-300, by - ay) + ax)
        inside ^= (np.count_nonzero(crosses, axis=1) % 2).astype(bool)
        dx, dy = bx - ax, by - ay
        t = np.clip(((x - ax) * dx + (y - ay) * dy) / np.maximum(dx * dx + dy * dy, 1e-300), 0, 1)
        wall = np.minimum(wall, np.hypot(ax + t * dx - x, ay + t * dy - y).min(axis=1))
    return inside, wall


def band_left(part, stops, z, radial, band, tol=0.01, step=0.05):
    """The wall band at height z, measured from the part on a grid of `step`:
    of the pocket's cross-section there (the air at z around the stops), the
    points farther than radial + band + tol from its walls (the core), how far
    the farthest lies from what the stops cut at z (each stop's tool at its
    radius there; lead-outs left out). {"z", "uncut", "at", "core_points",
    "thickest", "thickest_at"}: uncut 0 when every point of the core was cut;
    thickest, the band itself: the uncut point of the section farthest from
    its walls, less the radial allowance (0 when all is cut; a point within
    tol of a stop's disk is cut)."""
    deep = [s for s in stops if s.kind == "stop" and s.z < z - 1e-9]
    if not deep:
        raise ValueError("no stop reaches below z = %g" % z)
    air = air_at(part, z, (deep[0].x, deep[0].y))
    loops = _loops(air)
    disks = np.array([(s.x, s.y, radius_at(s.tool, s.z, z)) for s in deep])
    disks = disks[disks[:, 2] > 1e-9]
    bb = air.BoundBox
    xs = np.arange(bb.XMin + step / 2, bb.XMax, step)
    out = {"z": round(z, 4), "uncut": 0.0, "at": None, "core_points": 0, "thickest": 0.0, "thickest_at": None}
    limit = radial + band + tol
    rows = max(1, int(20000 // max(len(xs), 1)))
    for y0 in np.arange(bb.YMin + step / 2, bb.YMax, step * rows):
        ys = y0 + step * np.arange(rows)
        points = np.array([(x, y) for y in ys for x in xs])
        inside, wall = _inside_and_wall(points, loops)
        near = disks[(disks[:, 1] + disks[:, 2] >= ys[0]) & (disks[:, 1] - disks[:, 2] <= ys[-1])]
        room, walls = points[inside], wall[inside]
        if len(room):
            # Cut: within the measure's tolerance of a stop's disk (as the
            # core's gap below), so that a pin of a few micrometres between
            # three disks is not taken for a band as thick as the pocket.
            cut = np.zeros(len(room), bool) if not len(near) else \
                ((np.hypot(room[:, 0:1] - near[:, 0], room[:, 1:2] - near[:, 1]) - near[:, 2]) <= tol).any(axis=1)
            if (~cut).any():
                k = int(np.argmax(np.where(cut, -np.inf, walls)))
                if walls[k] - radial > out["thickest"]:
                    out["thickest"], out["thickest_at"] = float(walls[k] - radial), (round(room[k][0], 3),
                                                                                     round(room[k][1], 3))
        core = points[inside & (wall > limit)]
        if not len(core):
            continue
        out["core_points"] += len(core)
        if not len(near):
            gap = np.full(len(core), np.inf)
        else:
            gap = (np.hypot(core[:, 0:1] - near[:, 0], core[:, 1:2] - near[:, 1]) - near[:, 2]).min(axis=1)
        k = int(np.argmax(gap))
        if gap[k] > out["uncut"]:
            out["uncut"], out["at"] = float(gap[k]), (round(core[k][0], 3), round(core[k][1], 3))
    return out


def lift_needed(part, stop, radial, floor, tol=TOL, step=0.01, limit=5.0):
    """How much higher the stop had to be for its floor findings to pass (the
    radial ones do not change with Z): bisection to `step`, None past `limit`."""
    pf = part if isinstance(part, PartFaces) else PartFaces(part)

    def ok(dz):
        s = Stop(stop.tool, stop.x, stop.y, stop.z + dz, stop.op, stop.kind, stop.start)
        return all(f["distance"] >= f["need"] - tol for f in measure_stop(pf, s, radial, floor)
                   if not (f["vertical"] and f["contact"] == "beside"))

    if ok(0.0):
        return 0.0
    if not ok(limit):
        return None
    lo, hi = 0.0, limit
    while hi - lo > step:
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if ok(mid) else (mid, hi)
    return round(hi, 3)


def describe(report):
    """A few lines for a failure message or a log."""
    def one(r):
        if r is None:
            return "none within reach"
        s = r["stop"]
        return ("%.4f (need %.3f) %s %s at (%.3f, %.3f, %.3f), %s %s slope %s deg, stop %s (%.3f, %.3f, %.3f) %s"
                % (r["distance"], r["need"], r["face"], r.get("surface", ""), r["point"][0], r["point"][1],
                   r["point"][2], r["contact"], "vertical" if r["vertical"] else "", r.get("slope"), s["tool"],
                   s["x"], s["y"], s["z"], s["op"]))
    lines = ["%d stops, %d lead-outs in %.1f s; %d findings below the allowance at %d stops"
             % (report["stops"], report["lead_outs"], report["seconds"], report["failure_count"],
                report["failing_stops"]),
             "worst non-vertical: " + one(report["worst_floor"]),
             "worst vertical:     " + one(report["worst_radial"]),
             "worst lead-out:     " + one(report["worst_lead_out"])]
    return "\n".join(lines)
