"""Posted G-code checked against the part's own solid, not against the planner's input.

- every plunge bottom and every lead-out end: the tool's cylinder holds no part
  material within the floor allowance below it, nor within the radial allowance
  beside it (exact, with OpenCASCADE booleans on the part);
- slices: at each floor level, the part's empty space there (the cavity the
  selected floor lies in) is cut down to the floor stock limit, except within
  the radial allowance and the wall band of material at that height (real walls:
  nothing is excused along an open side, so no skin may stay there);
- rapids never pass through stock the program has not cut yet (a raster of the
  part's top surface under the Job's stock box, lowered by each cut in order).
The part's top surface is rasterised from its own tessellation (numpy)."""
import math

import numpy as np
from scipy import ndimage

import FreeCAD
import Part

from gcode import parse_gcode

V = FreeCAD.Vector
CELL = 0.1
TOL = 1e-3
# A rapid may pass within this of stock: the planner's rapids ignore slivers
# under 0.01 mm at the tool's edge (as machine_check.RAPID_TOL).
RAPID_TOL = 0.02


class Raster:
    """Heights over a grid of cell centres covering the part's bounding box."""

    def __init__(self, part, cell=CELL, margin=2.0):
        box = part.BoundBox
        self.cell = cell
        self.x0, self.y0 = box.XMin - margin, box.YMin - margin
        self.nx = int(math.ceil((box.XLength + 2 * margin) / cell))
        self.ny = int(math.ceil((box.YLength + 2 * margin) / cell))
        xs = self.x0 + (np.arange(self.nx) + 0.5) * cell
        ys = self.y0 + (np.arange(self.ny) + 0.5) * cell
        self.X, self.Y = np.meshgrid(xs, ys)
        self.top = self._top_surface(part)

    def _top_surface(self, part):
        """Highest part point over every cell (-inf where there is no part)."""
        top = np.full((self.ny, self.nx), -np.inf)
        points, triangles = part.tessellate(0.01)
        P = np.array([[p.x, p.y, p.z] for p in points])
        for a, b, c in triangles:
            pa, pb, pc = P[a], P[b], P[c]
            det = (pb[0] - pa[0]) * (pc[1] - pa[1]) - (pc[0] - pa[0]) * (pb[1] - pa[1])
            if abs(det) < 1e-12:
                continue  # a wall's triangle: no area in plan
            i0, i1, j0, j1 = self.window(min(pa[0], pb[0], pc[0]), max(pa[0], pb[0], pc[0]),
                                         min(pa[1], pb[1], pc[1]), max(pa[1], pb[1], pc[1]))
            if i0 >= i1 or j0 >= j1:
                continue
            X, Y = self.X[j0:j1, i0:i1], self.Y[j0:j1, i0:i1]
            u = ((pb[1] - pc[1]) * (X - pc[0]) + (pc[0] - pb[0]) * (Y - pc[1])) / ((pb[1] - pc[1]) * (pa[0] - pc[0]) + (pc[0] - pb[0]) * (pa[1] - pc[1]))
            v = ((pc[1] - pa[1]) * (X - pc[0]) + (pa[0] - pc[0]) * (Y - pc[1])) / ((pb[1] - pc[1]) * (pa[0] - pc[0]) + (pc[0] - pb[0]) * (pa[1] - pc[1]))
            w = 1 - u - v
            inside = (u >= -1e-9) & (v >= -1e-9) & (w >= -1e-9)
            z = u * pa[2] + v * pb[2] + w * pc[2]
            block = top[j0:j1, i0:i1]
            block[inside] = np.maximum(block[inside], z[inside])
        return top

    def window(self, xmin, xmax, ymin, ymax):
        i0 = max(0, int(math.floor((xmin - self.x0) / self.cell)))
        i1 = min(self.nx, int(math.ceil((xmax - self.x0) / self.cell)) + 1)
        j0 = max(0, int(math.floor((ymin - self.y0) / self.cell)))
        j1 = min(self.ny, int(math.ceil((ymax - self.y0) / self.cell)) + 1)
        return i0, i1, j0, j1

    def near_segment(self, a, b, r):
        """(window, mask) of the cells within r of the segment ab."""
        i0, i1, j0, j1 = self.window(min(a[0], b[0]) - r, max(a[0], b[0]) + r, min(a[1], b[1]) - r, max(a[1], b[1]) + r)
        X, Y = self.X[j0:j1, i0:i1], self.Y[j0:j1, i0:i1]
        dx, dy = b[0] - a[0], b[1] - a[1]
        L2 = dx * dx + dy * dy
        t = np.clip(((X - a[0]) * dx + (Y - a[1]) * dy) / L2, 0, 1) if L2 > 0 else np.zeros_like(X)
        d = np.hypot(X - (a[0] + t * dx), Y - (a[1] + t * dy))
        return (slice(j0, j1), slice(i0, i1)), d <= r


def moves(gcode, tools):
    """The program's moves in order: ("rapid"|"plunge"|"lead_out", tool diameter, from, to)
    with points (x, y, z); tools: {tool number: diameter}."""
    out = []
    tool = None
    x = y = z = None
    motion = None
    for codes, w in parse_gcode(gcode):
        if "M6" in codes and "T" in w:
            tool = tools[int(w["T"])]
        for c in codes:
            if c in ("G0", "G1"):
                motion = c
        if not any(k in w for k in "XYZ") or motion is None:
            continue
        nx, ny, nz = w.get("X", x), w.get("Y", y), w.get("Z", z)
        if x is not None and z is not None:
            if motion == "G0":
                out.append(("rapid", tool, (x, y, z), (nx, ny, nz)))
            elif (nx, ny) == (x, y) and nz < z:
                out.append(("plunge", tool, (x, y, z), (nx, ny, nz)))
            elif (nx, ny) != (x, y):
                out.append(("lead_out", tool, (x, y, z), (nx, ny, nz)))
        x, y, z = nx, ny, nz
    return out


def gouge(part, x, y, z, r, radial, floor):
    """Part material in the tool's cylinder at (x, y) stopping at z: the volume
    within the floor allowance below it, and within the radial allowance beside it."""
    top = part.BoundBox.ZMax + 1
    below = Part.makeCylinder(r - TOL, top - (z - floor + TOL), V(x, y, z - floor + TOL))
    beside = Part.makeCylinder(r + radial - TOL, top - (z + TOL), V(x, y, z + TOL))
    return part.common(below).Volume + part.common(beside).Volume


def check(part, stock_top, gcode, tools, radial, floor, wall_band, floor_stock, levels, seeds):
    """Findings of the G-code on the part (empty lists when it passes).

    levels: the floor heights to slice at; seeds: a point (x, y) on the selected
    floor of each level, which picks the part's cavity there."""
    raster = Raster(part)
    cut = np.full_like(raster.top, stock_top)
    report = {"gouges": [], "rapids_through_stock": [], "uncut": [], "plunges": 0, "lead_outs": 0}
    for kind, d, a, b in moves(gcode, tools):
        r = d / 2
        if kind == "rapid":
            low = min(a[2], b[2])
            if low >= stock_top:
                continue
            index, mask = raster.near_segment(a, b, r - RAPID_TOL)
            # The tool's bottom along the move is at least `low`; it must clear
            # what is left there (the part, or stock not yet cut).
            left = np.maximum(raster.top[index], cut[index])[mask]
            if left.size and left.max() > low + 0.02:
                report["rapids_through_stock"].append((a, b, float(left.max())))
            continue
        if kind == "plunge":
            report["plunges"] += 1
        else:
            report["lead_outs"] += 1
        lost = gouge(part, b[0], b[1], b[2], r, radial, floor)
        if lost > 1e-6:
            report["gouges"].append((kind, d, b, lost))
        index, mask = raster.near_segment(a, b, r)
        block = cut[index]
        block[mask] = np.minimum(block[mask], b[2])
    for level, seed in zip(levels, seeds):
        report["uncut"] += uncut(raster, cut, level, seed, radial, floor, wall_band, floor_stock)
    return report


def uncut(raster, cut, level, seed, radial, floor, wall_band, floor_stock):
    """Pieces of the cavity at `level` not cut down to the floor stock limit,
    farther than the allowance and the wall band from material: (area, x, y, width)."""
    height = level + floor + floor_stock + 0.05
    # Over the part (past an open side is the stock's margin, not the pocket) and below the level.
    empty = np.isfinite(raster.top) & (raster.top < level + 0.05)
    labels, _ = ndimage.label(empty)
    i = int((seed[0] - raster.x0) / raster.cell)
    j = int((seed[1] - raster.y0) / raster.cell)
    assert labels[j, i], ("no cavity at the seed", seed, level)
    cavity = labels == labels[j, i]
    material = raster.top >= height
    distance = ndimage.distance_transform_edt(~material) * raster.cell
    excused = distance <= radial + wall_band + 2 * raster.cell
    left = cavity & (cut > height) & ~excused
    pieces, n = ndimage.label(left)
    out = []
    for k in range(1, n + 1):
        cells = pieces == k
        area = cells.sum() * raster.cell ** 2
        if area < 4 * raster.cell ** 2:
            continue  # a raster's stair step along a curve
        jj, ii = np.argwhere(cells)[0]
        out.append((round(float(area), 3), round(float(raster.X[jj, ii]), 2), round(float(raster.Y[jj, ii]), 2),
                    round(float(distance[cells].max()), 2)))
    return out
