"""An independent reader of posted G-code and a fine height field of the stock
to replay it on (numpy): what the tests and benchmarks check plans against,
sharing no code with the planner or the addon's own replay (rest.py).

G0/G1/G2/G3 (XY plane, I J), G81/G82/G83/G73 with G98/G99 expanded into their
moves, G4 and M6; absolute mm only (G20 and G91 are refused).
"""
import math
import re
from collections import namedtuple

import numpy as np

from freecad_plugin import compat


def tools_of(job):
    """{tool number: (radius, corner radius)} of the Job's tool controllers, from their bits."""
    tools = {}
    for tc in job.Tools.Group:
        bit = tc.Tool
        r = float(bit.Diameter) / 2
        shape = compat.bit_shape(bit)
        if "ball" in shape:
            rc = r
        elif "bull" in shape:
            rc = float(getattr(bit, "CornerRadius", 0) or (r - float(getattr(bit, "FlatRadius", r))))
        else:
            rc = 0.0
        tools[int(tc.ToolNumber)] = (r, rc)
    return tools


# -- the G-code reader -----------------------------------------------------------------
WORD = re.compile(r"([A-Z])\s*([-+]?[0-9]*\.?[0-9]+)")
Move = namedtuple("Move", "rapid tool a b feed")  # a, b: (x, y, z)
Program = namedtuple("Program", "moves tool_changes dwell")
CANNED = ("G73", "G81", "G82", "G83")
PECK_CLEARANCE = 0.254  # LinuxCNC's rapid back down above the last peck (0.010 in)


def blocks(text):
    """Each line's words [(letter, value)], comments removed."""
    for line in text.splitlines():
        line = re.sub(r"\(.*?\)", "", line).split(";")[0].upper()
        words = [(k, float(v)) for k, v in WORD.findall(line)]
        if words:
            yield words


def arc_points(a, b, w, clockwise):
    """G2/G3 in the XY plane (I J from the start), as chords of at most 5 degrees."""
    cx, cy = a[0] + w.get("I", 0.0), a[1] + w.get("J", 0.0)
    r = math.hypot(a[0] - cx, a[1] - cy)
    t0, t1 = math.atan2(a[1] - cy, a[0] - cx), math.atan2(b[1] - cy, b[0] - cx)
    sweep = (t0 - t1) % (2 * math.pi) if clockwise else (t1 - t0) % (2 * math.pi)
    sweep = sweep or 2 * math.pi
    n = max(1, int(math.ceil(sweep / math.radians(5))))
    sign = -1 if clockwise else 1
    return [(cx + r * math.cos(t0 + sign * sweep * k / n), cy + r * math.sin(t0 + sign * sweep * k / n),
             a[2] + (b[2] - a[2]) * k / n) for k in range(1, n + 1)]


class Reader:
    """Interprets posted G-code (absolute, mm, XY plane) into straight moves."""

    def __init__(self):
        self.pos = (math.nan,) * 3
        self.motion, self.feed, self.tool, self.next_tool = None, 0.0, None, None
        self.retract, self.cycle_z = "G98", None
        self.moves, self.tool_changes, self.dwell = [], 0, 0.0

    def go(self, target, rapid):
        # An axis never set yet starts where it is going (no length).
        a = tuple(t if math.isnan(p) else p for p, t in zip(self.pos, target))
        if a != target:
            self.moves.append(Move(rapid, self.tool, a, target, None if rapid else self.feed))
        self.pos = target

    def block(self, words):
        codes = ["%s%d" % (k, round(v)) if v == int(v) else "%s%g" % (k, v) for k, v in words if k in "GM"]
        w = {k: v for k, v in words if k not in "GMN"}
        self.feed = w.get("F", self.feed)
        if "T" in w:
            self.next_tool = int(w["T"])
        if "M6" in codes:
            self.tool, self.tool_changes = self.next_tool, self.tool_changes + 1
        for c in codes:
            if c in ("G98", "G99"):
                self.retract = c
            if c in ("G0", "G1", "G2", "G3", "G80") + CANNED:
                self.motion = None if c == "G80" else c
                if c not in CANNED:
                    self.cycle_z = None
            if c in ("G20", "G91"):
                raise ValueError("only mm and absolute coordinates are read: %s" % c)
        if "G4" in codes:
            self.dwell += w.get("P", 0.0)
            return
        if not any(k in w for k in "XYZ") or self.motion is None:
            return
        target = tuple(w.get(k, p) for k, p in zip("XYZ", self.pos))
        if self.motion in ("G0", "G1"):
            self.go(target, self.motion == "G0")
        elif self.motion in ("G2", "G3"):
            for p in arc_points(self.pos, target, w, self.motion == "G2"):
                self.go(p, False)
        else:
            self.cycle(target, w)

    def cycle(self, target, w):
        """A drilling cycle's moves: rapid to R, feed down (in pecks of Q for
        G83/G73), dwell (G82), rapid back to the initial level (G98) or R (G99)."""
        x, y, z = target
        if self.cycle_z is None:
            self.cycle_z = self.pos[2]
        r = w.get("R", self.cycle_z)
        clear = max(self.pos[2], r)
        self.go((self.pos[0], self.pos[1], clear), True)
        self.go((x, y, clear), True)
        self.go((x, y, r), True)
        q = w.get("Q", 0.0) if self.motion in ("G73", "G83") else 0.0
        depth = r
        while depth > z + 1e-9:
            depth = max(z, depth - q) if q > 0 else z
            self.go((x, y, depth), False)
            if depth > z + 1e-9:  # clear the chips, then back down just above the last depth
                self.go((x, y, r if self.motion == "G83" else depth + PECK_CLEARANCE), True)
                self.go((x, y, depth + PECK_CLEARANCE), True)
        if self.motion == "G82":
            self.dwell += w.get("P", 0.0)
        self.go((x, y, max(self.cycle_z, r) if self.retract == "G98" else r), True)


def read_program(text):
    reader = Reader()
    for words in blocks(text):
        reader.block(words)
    return Program(reader.moves, reader.tool_changes, reader.dwell)


# -- the height field ---------------------------------------------------------------------
class Stock:
    """The stock's top as a height field (cell centres), cut by tool moves."""

    def __init__(self, box, cell):
        self.cell, self.x0, self.y0, self.top = cell, box.XMin, box.YMin, box.ZMax
        nx, ny = int(math.ceil(box.XLength / cell)), int(math.ceil(box.YLength / cell))
        self.xs = box.XMin + (np.arange(nx) + 0.5) * cell
        self.ys = box.YMin + (np.arange(ny) + 0.5) * cell
        self.z = np.full((ny, nx), box.ZMax)

    def cut(self, a, b, tool):
        """Sweep the tool (radius, corner radius) from a to b; the volume it removes (mm3).
        A move that also changes Z is cut in pieces of at most half a cell in Z, each at its higher end."""
        if min(a[2], b[2]) >= self.top:
            return 0.0
        if abs(a[0] - b[0]) < 1e-9 and abs(a[1] - b[1]) < 1e-9:
            return self.sweep(a, a, min(a[2], b[2]), tool)
        n = max(1, int(math.ceil(abs(b[2] - a[2]) / (self.cell / 2))))
        pts = [tuple(a[i] + (b[i] - a[i]) * k / n for i in range(3)) for k in range(n + 1)]
        return sum(self.sweep(p, q, max(p[2], q[2]), tool) for p, q in zip(pts, pts[1:]))

    def sweep(self, a, b, z, tool):
        r, rc = tool
        i0, i1 = self.index(min(a[0], b[0]) - r, self.x0), self.index(max(a[0], b[0]) + r, self.x0) + 1
        j0, j1 = self.index(min(a[1], b[1]) - r, self.y0), self.index(max(a[1], b[1]) + r, self.y0) + 1
        i0, j0, i1, j1 = max(i0, 0), max(j0, 0), min(i1, len(self.xs)), min(j1, len(self.ys))
        if i0 >= i1 or j0 >= j1:
            return 0.0
        d = segment_distance(self.xs[None, i0:i1], self.ys[j0:j1, None], a, b)
        t = np.clip(d - (r - rc), 0.0, rc)
        height = np.where(d <= r, z + rc - np.sqrt(np.maximum(rc * rc - t * t, 0.0)), np.inf)
        window = self.z[j0:j1, i0:i1]  # a view: cut in place
        removed = float(np.maximum(window - height, 0.0).sum()) * self.cell ** 2
        np.minimum(window, height, out=window)
        return removed

    def index(self, v, origin):
        return int(math.floor((v - origin) / self.cell))


def segment_distance(x, y, a, b):
    dx, dy = b[0] - a[0], b[1] - a[1]
    ll = dx * dx + dy * dy
    t = 0.0 if ll == 0 else np.clip(((x - a[0]) * dx + (y - a[1]) * dy) / ll, 0.0, 1.0)
    return np.hypot(x - a[0] - t * dx, y - a[1] - t * dy)


def replay(program, stock, tools):
    """Cut every move; volumes removed by feeds and by rapids, and the feed length that cut nothing."""
    feed = rapid = air = 0.0
    for m in program.moves:
        v = stock.cut(m.a, m.b, tools[m.tool])
        if m.rapid:
            rapid += v
        else:
            feed += v
            air += math.dist(m.a, m.b) if v < 1.0 else 0.0  # below 1 mm3: feeding through air
    return {"removed": feed + rapid, "by_rapids": rapid, "air_length": air,
            "feed_length": sum(math.dist(m.a, m.b) for m in program.moves if not m.rapid)}


def part_surface(shape, stock, empty=None):
    """The part's top surface z at each cell (the highest upward facet of a fine
    mesh over the cell centre); `empty` (the stock's top) where no part is."""
    import MeshPart
    mesh = MeshPart.meshFromShape(Shape=shape, LinearDeflection=0.02, AngularDeflection=0.1)
    points, facets = mesh.Topology
    p = np.array([[v.x, v.y, v.z] for v in points])[np.array(facets)]
    normal = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
    up = normal[:, 2] > 1e-3 * np.linalg.norm(normal, axis=1)  # walls (normal z about 0) cast no surface
    surface = np.full(stock.z.shape, -np.inf)
    for tri in p[up]:
        raster_triangle(surface, stock, tri)
    surface[np.isinf(surface)] = stock.top if empty is None else empty
    return surface


def raster_triangle(surface, stock, tri):
    i0, i1 = stock.index(tri[:, 0].min(), stock.x0), stock.index(tri[:, 0].max(), stock.x0) + 1
    j0, j1 = stock.index(tri[:, 1].min(), stock.y0), stock.index(tri[:, 1].max(), stock.y0) + 1
    i0, j0, i1, j1 = max(i0, 0), max(j0, 0), min(i1 + 1, len(stock.xs)), min(j1 + 1, len(stock.ys))
    if i0 >= i1 or j0 >= j1:
        return
    x, y = np.meshgrid(stock.xs[i0:i1], stock.ys[j0:j1])
    (x0, y0, z0), (x1, y1, z1), (x2, y2, z2) = tri
    det = (y1 - y2) * (x0 - x2) + (x2 - x1) * (y0 - y2)
    l0 = ((y1 - y2) * (x - x2) + (x2 - x1) * (y - y2)) / det
    l1 = ((y2 - y0) * (x - x2) + (x0 - x2) * (y - y2)) / det
    l2 = 1 - l0 - l1
    inside = (l0 >= -1e-9) & (l1 >= -1e-9) & (l2 >= -1e-9)
    z = np.where(inside, l0 * z0 + l1 * z1 + l2 * z2, -np.inf)
    surface[j0:j1, i0:i1] = np.maximum(surface[j0:j1, i0:i1], z)


# -- holders and shanks -----------------------------------------------------------------
def holder_hits(program, stock, tools, holders, clearance, slack=None):
    """Replays the program on the stock (cutting it as it goes) and checks, before
    each move, that every part of the tool wider than its cutter keeps
    `clearance` from the stock under it: holders = {tool number: [(mm above the
    tip where the part starts, its radius)]}. A move is checked at its lowest
    tip height along its whole XY segment. The raster's cuts may reach up to
    `slack` (default: a cell) beyond the true tool, so the search is that much
    narrower. Returns (hits, the worst mm into the clearance, the first hit's move)."""
    slack = stock.cell if slack is None else slack
    hits, worst, first = 0, 0.0, None
    for m in program.moves:
        z = min(m.a[2], m.b[2])
        r = tools[m.tool][0]
        for start, radius in holders.get(m.tool, []):
            if radius <= r:
                continue
            reach = radius + clearance - slack
            i0 = max(stock.index(min(m.a[0], m.b[0]) - reach, stock.x0), 0)
            i1 = min(stock.index(max(m.a[0], m.b[0]) + reach, stock.x0) + 1, len(stock.xs))
            j0 = max(stock.index(min(m.a[1], m.b[1]) - reach, stock.y0), 0)
            j1 = min(stock.index(max(m.a[1], m.b[1]) + reach, stock.y0) + 1, len(stock.ys))
            if i0 >= i1 or j0 >= j1:
                continue
            d = segment_distance(stock.xs[None, i0:i1], stock.ys[j0:j1, None], m.a, m.b)
            under = stock.z[j0:j1, i0:i1][d <= reach]
            if under.size == 0:
                continue
            gap = z + start - float(under.max())
            if gap < clearance - 1e-6:
                hits += 1
                worst = max(worst, clearance - gap)
                first = first or m
        stock.cut(m.a, m.b, tools[m.tool])
    return hits, worst, first
