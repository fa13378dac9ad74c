"""Independent checks of a plan with plain Python and shapely (GEOS), not the planner's code."""
import math

from shapely.geometry import Point, Polygon
from shapely.ops import unary_union


def wall_distance(loops, x, y):
    best = math.inf
    for loop in loops:
        n = len(loop)
        for i in range(n):
            (ax, ay), (bx, by) = loop[i], loop[(i + 1) % n]
            dx, dy = bx - ax, by - ay
            l2 = dx * dx + dy * dy
            t = 0.0 if l2 == 0 else max(0.0, min(1.0, ((x - ax) * dx + (y - ay) * dy) / l2))
            best = min(best, math.hypot(x - ax - t * dx, y - ay - t * dy))
    return best


def inside(loops, x, y):
    inside_ = False
    for loop in loops:
        n = len(loop)
        for i in range(n):
            (ax, ay), (bx, by) = loop[i - 1], loop[i]
            if (ay > y) != (by > y) and ax + (y - ay) / (by - ay) * (bx - ax) > x:
                inside_ = not inside_
    return inside_


def assert_no_gouge(data, plan):
    loops = [data["boundary"]] + data.get("islands", [])
    radial = data.get("allowance", {}).get("radial", 0.0)
    for p in plan["plunges"]:
        assert inside(loops, p["x"], p["y"]), p
        clearance = wall_distance(loops, p["x"], p["y"])
        assert clearance >= p["diameter"] / 2 + radial - 1e-6, (p, clearance)


def coverage(data, plan):
    """Covered fraction of the accessible region, measured with GEOS."""
    _, _, accessible, disks = accessible_and_disks(data, plan)
    return accessible.intersection(disks).area / accessible.area


def accessible_and_disks(data, plan):
    pocket = Polygon(data["boundary"], data.get("islands", []))
    radial = data.get("allowance", {}).get("radial", 0.0)
    tools = data["tools"] if isinstance(data["tools"], list) else data["tool_library"]
    r_min = min(t["diameter"] for t in tools) / 2
    accessible = pocket.buffer(-(radial + r_min), resolution=64).buffer(r_min, resolution=64)
    disks = unary_union([Point(p["x"], p["y"]).buffer(p["diameter"] / 2, resolution=64) for p in plan["plunges"]])
    return pocket, radial, accessible, disks


def _pieces(geometry):
    if geometry.is_empty:
        return []
    return list(geometry.geoms) if hasattr(geometry, "geoms") else [geometry]


def core_left(data, plan, band):
    """Areas of the pieces of the core (the accessible region farther than
    radial allowance + band from the walls) that no plunge disk covers."""
    pocket, radial, accessible, disks = accessible_and_disks(data, plan)
    # The planner leaves the last 0.01 mm of the accessible outline (polygon chord errors).
    core = pocket.buffer(-(radial + band), resolution=64).intersection(accessible.buffer(-0.02, resolution=64))
    return sorted(p.area for p in _pieces(core.difference(disks)))


def wall_stock_left(data, plan, sliver=0.01):
    """The thickest material along the walls the plunges leave, beyond the radial
    allowance: the farthest vertex of the uncovered pieces from the walls (vertices
    on the accessible outline are on a wall or in a corner no tool reaches).
    Pieces under `sliver` mm^2 are the polygons' approximation of the disks."""
    pocket, radial, accessible, disks = accessible_and_disks(data, plan)
    loops = [data["boundary"]] + data.get("islands", [])
    outline = accessible.boundary
    worst = 0.0
    for piece in _pieces(accessible.difference(disks)):
        if piece.area < sliver:
            continue
        for ring in [piece.exterior] + list(piece.interiors):
            for x, y in ring.coords:
                if outline.distance(Point(x, y)) > 0.02:
                    worst = max(worst, wall_distance(loops, x, y) - radial)
    return worst
