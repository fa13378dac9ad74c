"""A G-code-level checker: runs a posted program against a simulated stock.

Independent of the planner's code: its own G-code reader, height field (numpy),
distance transform (scipy) and wall geometry (shapely). For every plunge it
measures what the tool meets in the stock the moves before it left, and checks
- the radial engagement against the tool's max_engagement (and min_engagement);
- a non-centre-cutting tool's core over removed material;
- the cut depth against the flute length;
- no gouge: plunges and lead-outs stay clear of walls, islands and floor;
- rapids never through stock.

Definitions (the same as the planner's, docs/plan-format.md "Real plunge mills"):
material under a plunge is stock more than SKIN above the tool's cutting
surface; the engagement is the most material along any one radius of the tool
(its radius into solid), sampled on this checker's raster (the exact measure
on polygon stock is engagement_check.py's). A plunge is a start, exempt from the engagement limits, when its disk
holds no cut cell at all (into solid), when all cut cells lie near its centre
(onto a pre-drilled hole), or for a non-centre-cutting tool at a point where a
start hole was drilled before.
"""
import math
import re

import numpy as np
from shapely.geometry import LineString, Point, Polygon

SKIN = 0.5
# Wall and floor contact allowed: the G-code's 4 decimals move a point by up to 7e-5 mm.
GOUGE_TOL = 1e-3
# A rapid may pass within this of stock (the planner ignores slivers under 0.01 mm).
RAPID_TOL = 0.02
WORD = re.compile(r"([A-Z])\s*([-+]?[0-9]*\.?[0-9]+)")


def profile(tool, rho):
    """Height of the tool's lower surface above its tip at distance rho (numpy)."""
    r = tool["diameter"] / 2
    shape = tool.get("shape", "flat")
    rc = r if shape == "ball" else tool.get("corner_radius", 0.0) if shape == "bull" else 0.0
    if rc <= 0:
        return np.zeros_like(rho)
    t = np.clip(rho - (r - rc), 0.0, rc)
    return rc - np.sqrt(np.maximum(0.0, rc * rc - t * t))


def floor_function(data):
    """The floor height z(x, y) of a plan input (flat or expression), numpy-vectorised."""
    floor = data["floor"]
    if "brep" in floor:
        return None  # BREP faces: the floor checks are FreeCAD's own (tests/freecad)
    if "z" in floor:
        return lambda x, y: np.full_like(np.asarray(x, dtype=float), floor["z"])
    expr = floor["expression"].replace("^", "**")
    names = {k: getattr(np, k) for k in ("sin", "cos", "tan", "exp", "sqrt", "abs", "minimum", "maximum")}
    names["log"] = np.log
    return lambda x, y: np.asarray(eval(expr, {"__builtins__": {}}, dict(names, x=x, y=y)), dtype=float) \
        + np.zeros_like(np.asarray(x, dtype=float))


def parse(text):
    """Blocks of G-code as (codes, words), comments removed."""
    blocks = []
    for line in text.splitlines():
        line = re.sub(r"\(.*?\)", "", line).split(";")[0].strip().upper()
        if not line:
            continue
        codes, words = [], {}
        for letter, value in WORD.findall(line):
            if letter in "GM":
                codes.append(letter + str(int(float(value))))
            else:
                words[letter] = float(value)
        blocks.append((codes, words))
    return blocks


class Check:
    """Runs G-code text over the stock of a plan input; `report` holds the findings."""

    def __init__(self, data, tools, spacing=None):
        self.data = data
        self.tools = {t["id"]: t for t in tools}
        self.radial = data.get("allowance", {}).get("radial", 0.0)
        self.floor_allowance = data.get("allowance", {}).get("floor", 0.0)
        self.floor = floor_function(data)
        self.pocket = Polygon(data["boundary"], data.get("islands", []))
        self.walls = self.pocket.boundary
        self.top = data.get("top_z", 0.0)
        r_max = max(t["diameter"] for t in tools) / 2
        r_min = min(t["diameter"] for t in tools) / 2
        x0, y0, x1, y1 = self.pocket.bounds
        self.lo = np.array([x0 - r_max - 1, y0 - r_max - 1])
        if spacing is None:
            limits = [t["max_engagement"] for t in tools if "max_engagement" in t]
            spacing = max(min([r_min / 8] + [v / 6 for v in limits]), math.sqrt((x1 - x0) * (y1 - y0) / 3e6))
        self.h = spacing
        self.n = (np.ceil((np.array([x1 + r_max + 1, y1 + r_max + 1]) - self.lo) / spacing)).astype(int) + 1
        self.z = np.full((self.n[1], self.n[0]), self.top, dtype=float)  # [row = y, col = x]
        self.holes = []  # (x, y) of plunges by centre-cutting tools into solid: start holes
        self.report = {"plunges": 0, "over_engaged": [], "thin": [], "core_on_material": [], "too_deep": [],
                       "rapid_through_stock": [], "gouges": [], "lead_outs": 0, "lead_out_into_material": [],
                       "max_engagement": {}, "starts": 0, "pecks": 0}

    # -- the height field ------------------------------------------------------
    def window(self, x, y, reach):
        """Index ranges and cell centres within reach of (x, y) (clipped to the grid)."""
        i0 = max(0, int(math.floor((x - reach - self.lo[0]) / self.h)))
        i1 = min(self.n[0] - 1, int(math.ceil((x + reach - self.lo[0]) / self.h)))
        j0 = max(0, int(math.floor((y - reach - self.lo[1]) / self.h)))
        j1 = min(self.n[1] - 1, int(math.ceil((y + reach - self.lo[1]) / self.h)))
        xs = self.lo[0] + (np.arange(i0, i1 + 1) + 0.5) * self.h
        ys = self.lo[1] + (np.arange(j0, j1 + 1) + 0.5) * self.h
        return (slice(j0, j1 + 1), slice(i0, i1 + 1)), np.meshgrid(xs, ys)

    def swept_max(self, a, b, r):
        """Highest stock under a disk of radius r swept from a to b (cells whose centre it covers,
        as the cuts: the stock of a cell is the stock at its centre)."""
        (sy, sx), (X, Y) = self.window((a[0] + b[0]) / 2, (a[1] + b[1]) / 2,
                                       math.dist(a, b) / 2 + r + self.h)
        d = self._segment_distance(X, Y, a, b)
        under = d <= r - RAPID_TOL
        return float(self.z[sy, sx][under].max()) if under.any() else -math.inf

    @staticmethod
    def _segment_distance(X, Y, a, b):
        ax, ay = a
        dx, dy = b[0] - ax, b[1] - ay
        l2 = dx * dx + dy * dy
        t = np.zeros_like(X) if l2 == 0 else np.clip(((X - ax) * dx + (Y - ay) * dy) / l2, 0.0, 1.0)
        return np.hypot(X - ax - t * dx, Y - ay - t * dy)

    def cut(self, tool, x, y, z):
        r = tool["diameter"] / 2
        (sy, sx), (X, Y) = self.window(x, y, r)
        rho = np.hypot(X - x, Y - y)
        inside = rho <= r
        surface = z + profile(tool, rho)
        block = self.z[sy, sx]
        block[inside] = np.minimum(block[inside], surface[inside])

    # -- the moves -------------------------------------------------------------
    def plunge(self, tool_id, x, y, z):
        tool = self.tools[tool_id]
        r = tool["diameter"] / 2
        rep = self.report
        rep["plunges"] += 1
        self.no_gouge(tool, x, y, z, "plunge")
        (sy, sx), (X, Y) = self.window(x, y, r + self.h)
        rho = np.hypot(X - x, Y - y)
        disk = rho <= r
        above = self.z[sy, sx] - (z + profile(tool, rho))
        material = disk & (above > SKIN)
        free = disk & ~material
        where = (round(x, 3), round(y, 3), round(z, 3), tool_id)
        if material.any():
            engagement = r if not free.any() else self.along_radii(sy, sx, x, y, z, tool)
            flute = tool.get("flute_length")
            if flute and float((self.z[sy, sx] - z)[disk & (above > 0)].max()) > flute + 1e-6:
                rep["too_deep"].append(where)
        else:
            engagement = 0.0
        hole = any(math.dist(hxy, (x, y)) < 1e-3 for hxy in self.holes)
        start = not free.any() or (free.any() and rho[free].max() <= 0.6 * r) or \
            (tool.get("center_cutting", True) is False and hole)
        if start:
            rep["starts"] += 1
        else:
            rep["max_engagement"][tool_id] = max(rep["max_engagement"].get(tool_id, 0.0), engagement)
            tol = 1.5 * self.h
            if "max_engagement" in tool and engagement > tool["max_engagement"] + tol:
                rep["over_engaged"].append(where + (engagement,))
            if "min_engagement" in tool and material.any() and engagement < tool["min_engagement"] - tol:
                rep["thin"].append(where + (engagement,))
        if tool.get("center_cutting", True) is False:
            core = disk & (rho <= tool["core_diameter"] / 2)
            if (core & (above > SKIN)).any():
                rep["core_on_material"].append(where)
        elif material.any() and material[np.unravel_index(np.argmin(np.where(disk, rho, np.inf)), rho.shape)]:
            self.holes.append((x, y))  # its centre cut solid: a start hole for others
        self.cut(tool, x, y, z)

    def peck_on(self, tool_id, x, y, z):
        """A pecked hole goes on down after clearing its chips: the same plunge."""
        tool = self.tools[tool_id]
        self.report["pecks"] += 1
        self.no_gouge(tool, x, y, z, "plunge")
        self.cut(tool, x, y, z)

    def along_radii(self, sy, sx, x, y, z, tool):
        """The most material along one radius: 720 radii, each sampled every
        half cell on the raster."""
        r = tool["diameter"] / 2
        a = np.linspace(0, 2 * np.pi, 720, endpoint=False)[:, None]
        t = (np.arange(max(8, int(np.ceil(2 * r / self.h)))) + 0.5) * (r / max(8, int(np.ceil(2 * r / self.h))))
        px, py = x + np.cos(a) * t, y + np.sin(a) * t
        i = np.clip(np.floor((px - self.lo[0]) / self.h).astype(int), 0, self.n[0] - 1)
        j = np.clip(np.floor((py - self.lo[1]) / self.h).astype(int), 0, self.n[1] - 1)
        above = self.z[j, i] - (z + profile(tool, np.broadcast_to(t, px.shape)))
        return float(((above > SKIN).sum(axis=1) * (r / len(t))).max())

    def no_gouge(self, tool, x, y, z, what):
        r = tool["diameter"] / 2
        p = Point(x, y)
        if not self.pocket.contains(p) or self.walls.distance(p) < r + self.radial - GOUGE_TOL:
            self.report["gouges"].append((what, "wall", round(x, 3), round(y, 3)))
        if self.floor is None:
            return
        (sy, sx), (X, Y) = self.window(x, y, r)
        rho = np.hypot(X - x, Y - y)
        disk = rho <= r
        floor = self.floor(X[disk], Y[disk]) + self.floor_allowance
        if np.any(z + profile(tool, rho[disk]) < floor - GOUGE_TOL):
            self.report["gouges"].append((what, "floor", round(x, 3), round(y, 3), round(z, 3)))

    def lead_out(self, tool_id, a, b, z):
        tool = self.tools[tool_id]
        r = tool["diameter"] / 2
        self.report["lead_outs"] += 1
        seg = LineString([a, b])
        if not self.pocket.contains(seg) or self.walls.distance(seg) < r + self.radial - GOUGE_TOL:
            self.report["gouges"].append(("lead-out", "wall", a, b))
        steps = max(2, int(math.ceil(math.dist(a, b) / (self.h / 2))))
        for k in range(1, steps + 1):
            x = a[0] + (b[0] - a[0]) * k / steps
            y = a[1] + (b[1] - a[1]) * k / steps
            self.no_gouge(tool, x, y, z, "lead-out")
        # Grazing at the flanks is allowed: no material under the moved tool
        # farther than half the lead-out beyond the plunge's own hole (the two
        # rasters' cells apart).
        (sy, sx), (X, Y) = self.window(b[0], b[1], r)
        rho = np.hypot(X - b[0], Y - b[1])
        material = (rho <= r) & (self.z[sy, sx] - (z + profile(tool, rho)) > SKIN)
        if material.any():
            bite = float((np.hypot(X - a[0], Y - a[1])[material] - r).max())
            if bite > 0.5 * math.dist(a, b) + 2 * self.h:
                self.report["lead_out_into_material"].append((a, b, z, round(bite, 3)))
        for k in range(1, steps + 1):
            self.cut(tool, a[0] + (b[0] - a[0]) * k / steps, a[1] + (b[1] - a[1]) * k / steps, z)

    def rapid(self, tool_id, a, b, za, zb):
        """A rapid from (a, za) to (b, zb): the tool's bottom never below the stock it passes."""
        if tool_id is None or (a == b and zb >= za):
            return
        r = self.tools[tool_id]["diameter"] / 2
        if self.swept_max(a, b, r) > min(za, zb) + 1e-6:
            self.report["rapid_through_stock"].append((a, b, round(za, 3), round(zb, 3)))

    def run(self, text):
        """Replays G0/G1 (modal), G81/G83 (G98/G99) and tool changes (T.. M6 or M6 T..); a
        feed down at the X Y of the last plunge, with no move sideways since, goes on
        with that plunge (the next peck of a pecked hole)."""
        tool = None
        x = y = None
        z = None
        motion = None
        retract_mode = "G98"
        in_hole = False  # a feed down since the last move sideways: a further one is the next peck
        for codes, w in parse(text):
            if "M6" in codes and "T" in w:
                tool = int(w["T"])
                in_hole = False
            for c in codes:
                if c in ("G0", "G1", "G81", "G82", "G83"):
                    motion = c
                elif c in ("G98", "G99"):
                    retract_mode = c
                elif c == "G80":
                    motion = None
            if not any(k in w for k in "XYZ") or motion is None:
                continue
            nx, ny, nz = w.get("X", x), w.get("Y", y), w.get("Z", z)
            if motion in ("G81", "G82", "G83"):
                initial = z
                self.rapid(tool, (x, y), (nx, ny), z, z)
                self.rapid(tool, (nx, ny), (nx, ny), z, w["R"])
                self.plunge(tool, nx, ny, nz)
                x, y, z = nx, ny, initial if retract_mode == "G98" else w["R"]
                continue
            if x is None or y is None or z is None:
                x, y, z = nx, ny, nz
                continue
            if (nx, ny) != (x, y):
                in_hole = False
            if motion == "G0":
                self.rapid(tool, (x, y), (nx, ny), z, nz)
            elif (nx, ny) == (x, y) and nz < z and in_hole:
                self.peck_on(tool, nx, ny, nz)
            elif (nx, ny) == (x, y) and nz < z:
                self.plunge(tool, nx, ny, nz)
                in_hole = True
            elif (nx, ny) != (x, y) and nz == z:
                self.lead_out(tool, (x, y), (nx, ny), z)
            x, y, z = nx, ny, nz
        return self.report


def check_program(data, tools, gcode, spacing=None):
    """The checker's report of a program for a plan input and its tools ("auto":
    the library the tool choice picked from, every one of which may cut)."""
    if isinstance(tools, str):
        tools = data["tool_library"]
    return Check(data, tools, spacing).run(gcode)


def assert_machinable(report, thin_allowed=None):
    """Every check passed (thin cuts: at most `thin_allowed` when given)."""
    for key in ("over_engaged", "core_on_material", "too_deep", "rapid_through_stock", "gouges",
                "lead_out_into_material"):
        assert not report[key], (key, report[key][:5], len(report[key]))
    if thin_allowed is not None:
        assert len(report["thin"]) <= thin_allowed, report["thin"][:5]
