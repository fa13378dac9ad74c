"""An exact radial-engagement checker, independent of the planner's code.

The plan's plunges are replayed in their posted order on polygon stock (shapely
polygons, GEOS): the pocket region (boundary minus islands) starts full of
material and each plunge removes its disk (a regular polygon whose sides stay
within CHORD mm of the circle). Before a plunge's disk is removed, its radial
engagement is measured: the most uncut material along any one radius of the
tool, from its axis to its rim,

    engagement = max over theta of length(segment(c, c + r (cos theta, sin theta)) & stock).

A crescent at the rim gives its thickness, a ridge crossing the disk through the
axis gives up to r, a plunge into solid gives r, a plunge into cut space 0.

The lengths are computed exactly, ray against polygon edges (numpy): every edge
of the stock near the disk is mapped to the fan of rays whose angles it spans
(half-open in angle, so a ray through a vertex is counted consistently), the
crossings of each ray are sorted along it and the pieces inside the material
summed up to the rim. A ray starts inside the material when it crosses the
(closed, clipped) stock an odd number of times, so every ray decides on its own
and no separate point-in-polygon test can disagree with it. The directions are
sampled every 360/N_ANGLES degrees and through every vertex of the stock in the
disk and every crossing of its edges with the rim (where the length has its
kinks and jumps), then refined around the largest values.

Several depth levels (plunges with different stop heights z): one polygon stock
per z band (between the distinct stop heights and top_z). A plunge stopping at z
removes its disk from every band above z, and its engagement is the largest over
those bands. Exact for flat floors and flat tools.

Plunges marked "start" are exempt from the limit (they are reported, never
counted as violations). For speed the stock is kept in square tiles; a plunge
reads and updates only the tiles its disk touches.
"""
import math

import numpy as np
from shapely.geometry import MultiPolygon, Polygon, box
from shapely.ops import clip_by_rect, unary_union

CHORD = 0.001      # mm: the removed disk polygon stays within this of the circle
N_ANGLES = 1440    # directions of the first pass (0.25 degrees)
REFINE = 32        # directions per refined half window
PEAKS = 12         # windows refined around the largest values
Z_TOL = 1e-6       # stop heights closer than this are one band


# ---------------------------------------------------------------------------
# Geometry helpers

def disk_polygon(x, y, r, chord=CHORD):
    """A regular polygon within `chord` of the circle: the vertices lie chord/2
    outside it and the sides' midpoints chord/2 inside (or closer)."""
    n = max(16, int(math.ceil(math.pi / math.acos(max(-1.0, 1.0 - chord / (r + chord / 2))))))
    n = int(math.ceil(n / 4.0)) * 4
    rv = r + chord / 2
    a = np.arange(n) * (2 * math.pi / n)
    return Polygon(np.column_stack([x + rv * np.cos(a), y + rv * np.sin(a)]))


def _polygons(geometry):
    if geometry is None or geometry.is_empty:
        return []
    if geometry.geom_type == "Polygon":
        return [geometry]
    if hasattr(geometry, "geoms"):
        out = []
        for g in geometry.geoms:
            out.extend(_polygons(g))
        return out
    return []  # points and lines have no area


def _clean(geometry):
    """Only the areal part of a boolean's result (a MultiPolygon, maybe empty)."""
    polys = [p for p in _polygons(geometry) if p.area > 0.0]
    if not polys:
        return None
    return polys[0] if len(polys) == 1 else MultiPolygon(polys)


def edges_of(geometry):
    """All edges of a polygonal geometry as an (E, 4) array ax, ay, bx, by."""
    parts = []
    for p in _polygons(geometry):
        for ring in [p.exterior] + list(p.interiors):
            xy = np.asarray(ring.coords)
            if len(xy) >= 4:
                parts.append(np.hstack([xy[:-1], xy[1:]]))
    if not parts:
        return np.zeros((0, 4))
    return np.vstack(parts)


# ---------------------------------------------------------------------------
# Ray lengths

TWO_PI = 2.0 * math.pi


def ray_lengths(edges, cx, cy, r, thetas, starts_inside=False):
    """Length inside the closed polygon(s) given by `edges` of each segment from
    (cx, cy) to (cx, cy) + r (cos t, sin t), for the sorted angles `thetas` in
    [0, 2 pi). The edges must form closed rings (a clipped stock does).
    With `starts_inside`, also whether each ray starts in the material."""
    m = len(thetas)
    out = np.zeros(m)
    none = (out, np.zeros(m, dtype=bool)) if starts_inside else out
    if len(edges) == 0 or m == 0:
        return none
    ax = edges[:, 0] - cx
    ay = edges[:, 1] - cy
    bx = edges[:, 2] - cx
    by = edges[:, 3] - cy
    pa = np.arctan2(ay, ax)
    pa = np.where(pa < 0.0, pa + TWO_PI, pa)
    pb = np.arctan2(by, bx)
    pb = np.where(pb < 0.0, pb + TWO_PI, pb)
    # The edge spans the angles from its lower end to its upper one (counterclockwise),
    # taken from the endpoint angles themselves so that the edges meeting at a vertex
    # agree on which rays pass through it.
    d = pb - pa
    d = np.where(d > math.pi, d - TWO_PI, np.where(d <= -math.pi, d + TWO_PI, d))
    ccw = d > 0.0
    lo = np.where(ccw, pa, pb)
    hi = np.where(ccw, pb, pa)
    # Rays t with lo <= t < hi (around the circle): index range [klo, khi).
    klo = np.searchsorted(thetas, lo, side="left")
    khi = np.searchsorted(thetas, hi, side="left")
    count = khi - klo
    wrap = hi < lo
    count = np.where(wrap, count + m, count)
    # An edge through c crosses its rays at t = 0: leaving it out only decides
    # on which side of it each ray starts (the parity below).
    count = np.where((ax * by - ay * bx) == 0.0, 0, count)
    keep = count > 0
    if not keep.any():
        return none
    e_idx = np.nonzero(keep)[0]
    cnt = count[keep]
    total = int(cnt.sum())
    starts = np.repeat(klo[keep], cnt)
    offs = np.arange(total) - np.repeat(np.cumsum(cnt) - cnt, cnt)
    k = (starts + offs) % m
    e = np.repeat(e_idx, cnt)
    th = thetas[k]
    ux, uy = np.cos(th), np.sin(th)
    Ax, Ay, Bx, By = ax[e], ay[e], bx[e], by[e]
    sa = ux * Ay - uy * Ax
    sb = ux * By - uy * Bx
    da = ux * Ax + uy * Ay
    db = ux * Bx + uy * By
    den = sb - sa
    with np.errstate(divide="ignore", invalid="ignore"):
        t = (da * sb - db * sa) / den
    # Near-parallel rays: keep the crossing within the edge's span of distances.
    ra = np.hypot(Ax, Ay)
    rb = np.hypot(Bx, By)
    t = np.where(np.isfinite(t), t, np.minimum(ra, rb))
    t = np.clip(t, 0.0, np.maximum(ra, rb))
    # Sort crossings by ray, then along the ray.
    order = np.lexsort((t, k))
    k = k[order]
    t = np.minimum(t[order], r)
    ncross = np.bincount(k, minlength=m)
    first = np.cumsum(ncross) - ncross
    j = np.arange(total) - first[k]                 # crossing's rank along its ray
    inside0 = (ncross[k] & 1).astype(bool)          # ray starts in material
    before = np.concatenate([[0.0], t[:-1]])
    before[first[ncross > 0]] = 0.0                  # first crossing of each ray starts at 0
    state = inside0 ^ ((j & 1).astype(bool))         # material just before crossing j
    seg = np.where(state, t - before, 0.0)
    out += np.bincount(k, weights=seg, minlength=m)
    if starts_inside:
        return out, (ncross & 1).astype(bool)
    return out


def radial_engagement(edges, cx, cy, r, n_angles=N_ANGLES, refine=True, centre=False):
    """The largest material length along one radius, and the angle where it is
    (with `centre`, also whether the axis lies in material: most rays start in it).
    Rays every 360/n_angles degrees and through the stock's vertices in the disk and
    its crossings of the rim (event_angles), then (refine) a finer fan around the
    largest ones."""
    coarse = np.arange(n_angles) * (TWO_PI / n_angles)
    if len(edges) == 0:
        return (0.0, 0.0, False) if centre else (0.0, 0.0)
    events = event_angles(edges, cx, cy, r) if refine else np.zeros(0)
    thetas = np.concatenate([coarse, events])
    order = np.argsort(thetas, kind="stable")
    thetas = thetas[order]
    lengths, inside = ray_lengths(edges, cx, cy, r, thetas, starts_inside=True)
    i = int(np.argmax(lengths))
    best, best_theta = float(lengths[i]), float(thetas[i])
    if refine and 0.0 < best < r - 1e-12:
        step = TWO_PI / n_angles
        centres = thetas[np.argsort(lengths)[-PEAKS:]]
        sub = (np.arange(1, 2 * REFINE) / REFINE - 1.0) * step  # (-step, step)
        fine = np.unique(np.mod((centres[:, None] + sub[None, :]).ravel(), TWO_PI))
        fl = ray_lengths(edges, cx, cy, r, fine)
        j = int(np.argmax(fl))
        if fl[j] > best:
            best, best_theta = float(fl[j]), float(fine[j])
    result = (min(best, r), best_theta)
    if centre:
        in_coarse = inside[np.argsort(order, kind="stable")[:n_angles]]
        return result + (bool(in_coarse.mean() > 0.5),)
    return result


EVENT_EPS = 1e-9  # rad: rays just either side of a vertex's direction


def event_angles(edges, cx, cy, r):
    """The directions where the length along a ray can have a kink or a jump: the
    stock's vertices within the disk and the points where its edges cross the
    rim. A maximum of the length lies there or where the length is smooth."""
    ax = edges[:, 0] - cx
    ay = edges[:, 1] - cy
    near = ax * ax + ay * ay <= r * r
    px, py = [ax[near]], [ay[near]]
    # edge a + s (b - a), |.| = r, 0 <= s <= 1
    dx = edges[:, 2] - edges[:, 0]
    dy = edges[:, 3] - edges[:, 1]
    qa = dx * dx + dy * dy
    qb = 2 * (ax * dx + ay * dy)
    qc = ax * ax + ay * ay - r * r
    disc = qb * qb - 4 * qa * qc
    ok = (disc >= 0.0) & (qa > 0.0)
    if ok.any():
        root = np.sqrt(disc[ok])
        for sgn in (-1.0, 1.0):
            s = (-qb[ok] + sgn * root) / (2 * qa[ok])
            inside = (s >= 0.0) & (s <= 1.0)
            px.append(ax[ok][inside] + s[inside] * dx[ok][inside])
            py.append(ay[ok][inside] + s[inside] * dy[ok][inside])
    px, py = np.concatenate(px), np.concatenate(py)
    if len(px) == 0:
        return np.zeros(0)
    phi = np.arctan2(py, px)
    phi = np.concatenate([phi - EVENT_EPS, phi, phi + EVENT_EPS])
    return np.unique(np.mod(phi, TWO_PI))


# ---------------------------------------------------------------------------
# Tiled polygon stock

class Stock:
    """Polygon stock kept in square tiles, so each plunge works on little."""

    def __init__(self, region, tile):
        self.tile = tile
        x0, y0, x1, y1 = region.bounds
        self.x0, self.y0 = x0, y0
        self.nx = max(1, int(math.ceil((x1 - x0) / tile)))
        self.ny = max(1, int(math.ceil((y1 - y0) / tile)))
        self.tiles = {}
        for i in range(self.nx):
            for j in range(self.ny):
                bx0, by0 = x0 + i * tile, y0 + j * tile
                piece = _clean(region.intersection(box(bx0, by0, bx0 + tile, by0 + tile)))
                if piece is not None:
                    self.tiles[(i, j)] = piece

    def _keys(self, bx0, by0, bx1, by1):
        i0 = max(0, int(math.floor((bx0 - self.x0) / self.tile)))
        i1 = min(self.nx - 1, int(math.floor((bx1 - self.x0) / self.tile)))
        j0 = max(0, int(math.floor((by0 - self.y0) / self.tile)))
        j1 = min(self.ny - 1, int(math.floor((by1 - self.y0) / self.tile)))
        return [(i, j) for i in range(i0, i1 + 1) for j in range(j0, j1 + 1) if (i, j) in self.tiles]

    def edges_near(self, x, y, r):
        """Edges of the stock clipped to the square around the disk (closed rings)."""
        m = r + 2 * CHORD
        bx0, by0, bx1, by1 = x - m, y - m, x + m, y + m
        parts = []
        for key in self._keys(bx0, by0, bx1, by1):
            g = self.tiles[key]
            gx0, gy0, gx1, gy1 = g.bounds
            if gx0 >= bx0 and gy0 >= by0 and gx1 <= bx1 and gy1 <= by1:
                parts.append(edges_of(g))
            elif gx1 > bx0 and gx0 < bx1 and gy1 > by0 and gy0 < by1:
                parts.append(edges_of(clip_by_rect(g, bx0, by0, bx1, by1)))
        if not parts:
            return np.zeros((0, 4))
        return np.vstack(parts)

    def remove(self, disk):
        bx0, by0, bx1, by1 = disk.bounds
        for key in self._keys(bx0, by0, bx1, by1):
            g = self.tiles[key]
            gx0, gy0, gx1, gy1 = g.bounds
            if gx1 <= bx0 or gx0 >= bx1 or gy1 <= by0 or gy0 >= by1:
                continue
            piece = _clean(g.difference(disk))
            if piece is None:
                del self.tiles[key]
            else:
                self.tiles[key] = piece

    def geometry(self):
        """The whole stock as one geometry (for tests and pictures)."""
        return unary_union(list(self.tiles.values()))


# ---------------------------------------------------------------------------
# Replaying a plan

def tool_limits(data):
    """max_engagement by tool id (inf where unlimited), from tools or tool_library."""
    tools = []
    for key in ("tools", "tool_library"):
        if isinstance(data.get(key), list):
            tools.extend(data[key])
    limits = {}
    for i, t in enumerate(sorted(tools, key=lambda t: -t["diameter"])):
        tid = t.get("id", i + 1)
        limits.setdefault(tid, t.get("max_engagement", math.inf))
    return limits


def pocket_region(data):
    return Polygon(data["boundary"], data.get("islands", [])).buffer(0)


def z_bands(plan, top_z):
    """Band bottoms, ascending: the distinct stop heights below top_z."""
    zs = sorted(p["z"] for p in plan["plunges"])
    bottoms = []
    for z in zs:
        if z >= top_z - Z_TOL:
            continue
        if not bottoms or z > bottoms[-1] + Z_TOL:
            bottoms.append(z)
    return bottoms


def replay(data, plan, n_angles=N_ANGLES, refine=True, tile=None):
    """Every plunge of the plan in its posted order, with the engagement measured
    on the polygon stock left by the plunges before it: a list of dicts
    {index, tool_id, x, y, z, r, engagement, theta, limit, start, reported,
    centre_in_material}. `reported` is the plan's own "engagement" field."""
    region = pocket_region(data)
    plunges = plan["plunges"]
    if not plunges:
        return []
    top_z = data.get("top_z", 0.0)
    bottoms = z_bands(plan, top_z)
    rmax = max(p["diameter"] for p in plunges) / 2
    if tile is None:
        tile = max(4.0 * rmax, 1.0)
    stocks = [Stock(region, tile) for _ in bottoms]
    limits = tool_limits(data)
    results = []
    for index, p in enumerate(plunges):
        x, y, r, z = p["x"], p["y"], p["diameter"] / 2, p["z"]
        cut = [b for b, bottom in enumerate(bottoms) if bottom >= z - Z_TOL]
        engagement, theta, centre = 0.0, 0.0, False
        for b in cut:
            edges = stocks[b].edges_near(x, y, r)
            if len(edges):
                e, th, inside = radial_engagement(edges, x, y, r, n_angles, refine, centre=True)
                if e > engagement:
                    engagement, theta = e, th
                centre = centre or inside
        results.append({
            "index": index, "tool_id": p.get("tool_id"), "x": x, "y": y, "z": z, "r": r,
            "engagement": engagement, "theta": theta,
            "limit": limits.get(p.get("tool_id"), math.inf),
            "start": bool(p.get("start", False)), "start_hole": bool(p.get("start_hole", False)),
            "reported": p.get("engagement"), "centre_in_material": bool(centre),
        })
        if cut:
            disk = disk_polygon(x, y, r)
            for b in cut:
                stocks[b].remove(disk)
    return results


def over_limit(data, plan, slack=0.01, results=None):
    """The non-start plunges cutting more than their tool's max_engagement + slack."""
    if results is None:
        results = replay(data, plan)
    return [q for q in results if not q["start"] and q["engagement"] > q["limit"] + slack]


def summary(results, slack=0.01):
    """Counts per tool: plunges, starts, violations and the worst excess."""
    out = {}
    for q in results:
        s = out.setdefault(q["tool_id"], {"plunges": 0, "starts": 0, "over": 0, "max_excess": 0.0,
                                          "max_engagement": 0.0, "limit": q["limit"]})
        s["plunges"] += 1
        if q["start"]:
            s["starts"] += 1
            continue
        s["max_engagement"] = max(s["max_engagement"], q["engagement"])
        excess = q["engagement"] - q["limit"]
        if excess > slack:
            s["over"] += 1
            s["max_excess"] = max(s["max_excess"], excess)
    return out
