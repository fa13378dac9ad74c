"""The G-code replay of rest plunging: the Job's stock solid as the top of
the material per cell, and the Path commands of earlier operations as straight
tool tip moves (G0-G3, canned cycles, as a post writes them), each swept over
that grid with its tool's shape by the planner (plunge.sweep). rest.py says
which operations and which stock; this module only replays.

App side: never imports GUI code.
"""
import math

import FreeCAD

from freecad_plugin import compat, planner, tools

translate = FreeCAD.Qt.translate

# Canned drilling cycles: the tool feeds to Z from R and comes back.
CYCLES = ("G73", "G81", "G82", "G83", "G85")


def grid_over(lo, hi, h, top):
    nx = max(1, int(math.ceil((hi[0] - lo[0]) / h)))
    ny = max(1, int(math.ceil((hi[1] - lo[1]) / h)))
    return {"origin": [lo[0], lo[1]], "spacing": h, "nx": nx, "ny": ny, "top": [top] * (nx * ny)}


def stock_tops(shape, grid, top_z):
    """The top of the stock solid over each cell's centre, at most top_z; cells
    with no stock over them hold the stock's bottom. A box is read from its
    bounds; any other solid from its triangulation (the highest triangle over
    the centre)."""
    import numpy as np
    box = shape.BoundBox
    nx, ny, h = grid["nx"], grid["ny"], grid["spacing"]
    x0, y0 = grid["origin"]
    xs = x0 + (np.arange(nx) + 0.5) * h
    ys = y0 + (np.arange(ny) + 0.5) * h
    bottom = box.ZMin
    if abs(shape.Volume - box.XLength * box.YLength * box.ZLength) < 1e-6 * max(shape.Volume, 1.0):
        inside = ((xs[None, :] >= box.XMin) & (xs[None, :] <= box.XMax)
                  & (ys[:, None] >= box.YMin) & (ys[:, None] <= box.YMax))
        tops = np.where(inside, min(box.ZMax, top_z), bottom)
        return tops.ravel().tolist()
    tops = np.full((ny, nx), -np.inf)
    points, triangles = shape.tessellate(h / 4.0)
    pts = np.array([(p.x, p.y, p.z) for p in points])
    for tri in triangles:
        _raster_triangle(pts[list(tri)], tops, x0, y0, h)
    return np.clip(np.where(np.isfinite(tops), tops, bottom), bottom, top_z).ravel().tolist()


def _raster_triangle(p, tops, x0, y0, h):
    """tops[j, i] = max(tops, the triangle's height over the cell centres under it)."""
    import numpy as np
    ny, nx = tops.shape
    i0, i1 = max(0, int((p[:, 0].min() - x0) // h)), min(nx - 1, int((p[:, 0].max() - x0) // h))
    j0, j1 = max(0, int((p[:, 1].min() - y0) // h)), min(ny - 1, int((p[:, 1].max() - y0) // h))
    if i0 > i1 or j0 > j1:
        return
    (ax, ay, az), (bx, by, bz), (cx, cy, cz) = p
    det = (by - cy) * (ax - cx) + (cx - bx) * (ay - cy)
    if abs(det) < 1e-12:  # a vertical face: the faces it joins hold the heights
        return
    X, Y = np.meshgrid(x0 + (np.arange(i0, i1 + 1) + 0.5) * h, y0 + (np.arange(j0, j1 + 1) + 0.5) * h)
    u = ((by - cy) * (X - cx) + (cx - bx) * (Y - cy)) / det
    v = ((cy - ay) * (X - cx) + (ax - cx) * (Y - cy)) / det
    w = 1 - u - v
    inside = (u >= -1e-9) & (v >= -1e-9) & (w >= -1e-9)
    z = np.where(inside, u * az + v * bz + w * cz, -np.inf)
    block = tops[j0:j1 + 1, i0:i1 + 1]
    np.maximum(block, z, out=block)


def cutter_of(tc):
    """The planner's tool for any tool controller, as a shape that never cuts
    more than the bit: flat, ball and bull as they are; a drill, chamfer or
    V-bit as a flat bottom at the height of its cone's rim."""
    bit = tc.Tool
    d = tools.diameter(tc)
    shape = compat.bit_shape(bit) or "endmill"
    if any(s in shape for s in ("ball", "bull", "endmill", "plunge")):
        spec = tools.spec(tc)
        return {k: spec[k] for k in ("diameter", "id", "shape", "corner_radius") if k in spec}, 0.0
    angle = tools.bit_length(bit, "TipAngle") or tools.bit_length(bit, "CuttingEdgeAngle") or 0.0
    tip = tools.bit_length(bit, "TipDiameter") or 0.0
    rise = (d - tip) / 2 / math.tan(math.radians(angle) / 2) if 0 < angle < 180 else 0.0
    return {"diameter": d, "id": tools.number(tc)}, rise


class Replay:
    """Path commands as straight tool tip moves, in program coordinates, as a
    post writes them: arcs in chords of at most `chord` error, canned cycles
    as their rapid to R, feed to Z and return (G98: to the level before the
    cycle; G99: to R)."""

    def __init__(self, start, chord):
        self.pos = list(start)
        self.chord = chord
        self.relative = False
        self.retract_to_r = False
        self.moves = []
        self.notes = set()

    def run(self, commands):
        for c in commands:
            self.command(c.Name.upper(), {k.upper(): v for k, v in c.Parameters.items()})
        return self.moves

    def target(self, p):
        axes = "XYZ"
        if self.relative:
            return [self.pos[k] + p.get(axes[k], 0.0) for k in range(3)]
        return [p.get(axes[k], self.pos[k]) for k in range(3)]

    def line(self, to):
        if to != self.pos:
            self.moves.append(tuple(self.pos) + tuple(to))
        self.pos = list(to)

    def command(self, name, p):
        if name in ("G90", "G91"):
            self.relative = name == "G91"
        elif name in ("G98", "G99"):
            self.retract_to_r = name == "G99"
        elif name in ("G0", "G00", "G1", "G01"):
            self.line(self.target(p))
        elif name in ("G2", "G02", "G3", "G03"):
            self.arc(name in ("G2", "G02"), p)
        elif name in CYCLES:
            self.cycle(p)
        elif name in ("G20", "G18", "G19", "G28", "G53"):
            self.notes.add(name)
        elif name.startswith("G38"):  # a probe move cuts nothing: it only moves
            self.pos = self.target(p)

    def arc(self, clockwise, p):
        start, end = self.pos, self.target(p)
        if "R" in p or ("I" not in p and "J" not in p):
            self.notes.add("arc without I/J")
            self.line(end)
            return
        cx, cy = start[0] + p.get("I", 0.0), start[1] + p.get("J", 0.0)
        r = math.hypot(start[0] - cx, start[1] - cy)
        a0 = math.atan2(start[1] - cy, start[0] - cx)
        a1 = math.atan2(end[1] - cy, end[0] - cx)
        sweep = a1 - a0
        if clockwise and sweep >= -1e-12:
            sweep -= 2 * math.pi
        elif not clockwise and sweep <= 1e-12:
            sweep += 2 * math.pi
        step = 2 * math.acos(max(-1.0, 1 - self.chord / r)) if r > self.chord else math.pi / 4
        n = max(1, int(math.ceil(abs(sweep) / max(step, 1e-3))))
        for k in range(1, n + 1):
            t = k / n
            a = a0 + sweep * t
            self.line([cx + r * math.cos(a), cy + r * math.sin(a), start[2] + (end[2] - start[2]) * t]
                      if k < n else end)

    def cycle(self, p):
        before = self.pos[2]
        x, y, z = self.target({k: v for k, v in p.items() if k in "XYZ"})
        r = p.get("R", before)
        self.line([x, y, before])
        self.line([x, y, r])
        self.line([x, y, z])
        self.line([x, y, r if self.retract_to_r else max(r, before)])


def replay_onto(grid, ops, stock_top, progress=None):
    """Sweeps the operations' paths (operation, tool controller), in order, over
    the grid; the notes on commands not replayed."""
    plunge = planner.planner()
    notes = []
    for op, tc in ops:
        replay = Replay((0.0, 0.0, stock_top + 1000.0), grid["spacing"] / 4.0)
        moves = replay.run(op.Path.Commands)
        tool, rise = cutter_of(tc)
        if rise:
            moves = [(a, b, c + rise, d, e, f + rise) for a, b, c, d, e, f in moves]
        grid["top"] = plunge.sweep(grid, tool, moves, progress)
        if replay.notes:
            notes.append(translate("PlungeRough", "%s: %s not replayed (taken as cutting nothing)")
                         % (op.Label, ", ".join(sorted(replay.notes))))
    return notes
