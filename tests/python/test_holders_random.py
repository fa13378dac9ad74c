"""Holders and shanks on random deep pockets: every posted move replayed on a
raster of this file's own (numpy and shapely, nothing of the planner), in the
order posted. The part (outside the boundary, inside the islands) stands at
top_z; each plunge and lead-out lowers the material under its tool. At every
move (the plunge, the lead-out, the rapid across at the retract height through
its `via` points) each part of the tool wider than its cutter (a wider shank
from the flutes' top, the holder from the stick-out up) keeps the holder
clearance from the material, and the flutes pass over it in the rapids.

The pockets are the exact-engagement test's varied shapes, made 35 to 70 mm
deep: short plungers held in holders that meet the walls, sometimes a long
slim one that reaches, a wider shank, an unknown holder diameter, pecks and
lead-outs on or off, flat or wavy floors. 40 pockets with PLUNGE_LONG_TESTS=1
(CI's native run), 16 without."""
import math
import os
import random

import numpy as np
import pytest
from shapely.geometry import Polygon
from shapely import vectorized

from test_engagement_exact import varied_pocket

POCKETS = 40 if os.environ.get("PLUNGE_LONG_TESTS") == "1" else 16
CELL = 0.25  # mm
SLACK = 0.75 * CELL  # the raster's disks are this much short of the tool's


def deep(seed):
    """A varied pocket made deep, its tools mounted."""
    data = varied_pocket(seed)
    rng = random.Random(5000 + seed)
    depth = rng.uniform(35, 70)
    if rng.random() < 0.3:
        data["floor"] = {"expression": "%.1f + 2*sin(0.15*x)*cos(0.1*y)" % -depth}
    else:
        data["floor"] = {"z": -depth}
    data["peck"] = rng.random() < 0.5
    data["lead_out"] = rng.choice([0.0, 0.5, 1.0])
    data["holder_clearance"] = rng.choice([0.5, 1.0, 2.0])
    for t in data["tools"]:
        d = t["diameter"]
        t["flute_length"] = round(rng.uniform(1.5, 3.0) * d, 1)
        t["stick_out"] = round(t["flute_length"] + rng.uniform(2, 25), 1)
        if rng.random() < 0.85:
            t["holder_diameter"] = round(d + rng.uniform(8, 30), 1)
        if rng.random() < 0.2:
            t["shank_diameter"] = round(d + rng.uniform(1, 4), 1)
    if len(data["tools"]) > 1 and rng.random() < 0.6:  # the smallest held far out: it reaches
        slim = data["tools"][-1]
        slim.pop("shank_diameter", None)
        slim.update(flute_length=round(depth * 0.8, 1), stick_out=round(depth + 15, 1),
                    holder_diameter=slim["diameter"] + 10)
    return data


class Raster:
    """Material tops on cells of CELL mm over the pocket and 40 mm around."""

    def __init__(self, data):
        region = Polygon(data["boundary"], data["islands"])
        x0, y0, x1, y1 = region.bounds
        self.x0, self.y0 = x0 - 40, y0 - 40
        nx, ny = int((x1 - x0 + 80) / CELL) + 1, int((y1 - y0 + 80) / CELL) + 1
        xs = self.x0 + (np.arange(nx) + 0.5) * CELL
        ys = self.y0 + (np.arange(ny) + 0.5) * CELL
        self.X, self.Y = np.meshgrid(xs, ys)
        self.pocket = vectorized.contains(region, self.X, self.Y)
        self.z = np.full(self.X.shape, float(data["top_z"]))

    def _near(self, a, b, r):
        """The window and the mask of cells within r of the segment a-b."""
        i0 = max(0, int((min(a[0], b[0]) - r - self.x0) / CELL) - 1)
        i1 = min(self.X.shape[1], int((max(a[0], b[0]) + r - self.x0) / CELL) + 2)
        j0 = max(0, int((min(a[1], b[1]) - r - self.y0) / CELL) - 1)
        j1 = min(self.X.shape[0], int((max(a[1], b[1]) + r - self.y0) / CELL) + 2)
        X, Y = self.X[j0:j1, i0:i1], self.Y[j0:j1, i0:i1]
        dx, dy = b[0] - a[0], b[1] - a[1]
        L2 = dx * dx + dy * dy
        t = np.clip(((X - a[0]) * dx + (Y - a[1]) * dy) / L2, 0, 1) if L2 > 0 else 0.0
        d = np.hypot(X - (a[0] + t * dx), Y - (a[1] + t * dy))
        return (slice(j0, j1), slice(i0, i1)), d <= r

    def highest(self, a, b, r):
        w, m = self._near(a, b, r)
        return float(self.z[w][m].max()) if m.any() else -math.inf

    def cut(self, a, b, r, z):
        w, m = self._near(a, b, r)
        m &= self.pocket[w]
        self.z[w][m] = np.minimum(self.z[w][m], z)


def parts_of(tool):
    """The tool's cylinders wider than its cutter: (from mm above the tip, radius)."""
    parts = []
    if "stick_out" not in tool:
        return parts
    if tool.get("shank_diameter", 0) > tool["diameter"]:
        parts.append((tool["flute_length"], 0.5 * tool["shank_diameter"]))
    parts.append((tool["stick_out"], 0.5 * tool["holder_diameter"] if "holder_diameter" in tool else 1e4))
    return parts


def collisions(data, plan):
    """Every posted move replayed: [(what, mm into the clearance or the stock)]."""
    stock = Raster(data)
    tools = {t["id"]: t for t in data["tools"]}
    c = data.get("holder_clearance", 1.0)
    found = []

    def holder(tool, a, b, z, what):
        for above, radius in parts_of(tool):
            gap = z + above - stock.highest(a, b, radius + c - SLACK)
            if gap < c - 1e-6:
                found.append((what + " (holder or shank)", c - gap))

    plunges = plan["plunges"]
    for i, p in enumerate(plunges):
        tool, r, at = tools[p["tool_id"]], 0.5 * p["diameter"], (p["x"], p["y"])
        # Rapid down to the approach height: over the material under the tool.
        if stock.highest(at, at, r - SLACK) > p["approach_z"] + 1e-6:
            found.append(("approach %d" % i, stock.highest(at, at, r - SLACK) - p["approach_z"]))
        holder(tool, at, at, p["z"], "plunge %d" % i)
        stock.cut(at, at, r, p["z"])
        end = at
        if "lead_out" in p:
            z = p.get("lead_out_z", p["z"])
            end = tuple(p["lead_out"])
            holder(tool, at, end, z, "lead-out %d" % i)
            stock.cut(at, end, r, z)
        if i + 1 < len(plunges) and plunges[i + 1]["tool_id"] == p["tool_id"]:
            way = [end] + [tuple(v) for v in p.get("via", [])] + [(plunges[i + 1]["x"], plunges[i + 1]["y"])]
            for a, b in zip(way, way[1:]):
                holder(tool, a, b, p["retract_z"], "move after %d" % i)
                over = stock.highest(a, b, r - SLACK) - p["retract_z"]
                if over > 1e-6:
                    found.append(("move after %d (the flutes)" % i, over))
    return found


@pytest.mark.parametrize("group", range(POCKETS // 8))
def test_random_deep_pockets_keep_holders_clear(plunge, group):
    for seed in range(8 * group, 8 * group + 8):
        data = deep(seed)
        plan = plunge.plan(data)
        found = collisions(data, plan)
        assert not found, "pocket %d: %d collisions, the first %s, the worst %.3f mm" % (
            seed, len(found), found[0][0], max(f[1] for f in found))
        # What a holder stopped is said, with the stick-out that would reach.
        stopped = {(p["tool_id"], p["x"], p["y"]) for p in plan["plunges"] if p.get("holder_limited")}
        said = [b for b in plan.get("broken_limits", []) if b["limit"] == "stick_out"]
        assert not said or stopped, "pocket %d" % seed
        for b in said:
            assert b["worst"] > b["asked"] and b["count"] >= 1, b


def test_the_replay_finds_a_holder_driven_into_the_walls(plunge):
    """The replay can fail: the same pocket planned without the holders,
    replayed with them, meets the walls."""
    data = {"boundary": [[0, 0], [80, 0], [80, 50], [0, 50]], "islands": [], "top_z": 0, "safe_z": 5,
            "floor": {"z": -50}, "allowance": {"radial": 0.3, "floor": 0.2},
            "tools": [{"id": 1, "diameter": 16, "flute_length": 30, "stick_out": 40, "holder_diameter": 40}]}
    blind = dict(data, tools=[{"id": 1, "diameter": 16, "flute_length": 30}])
    found = collisions(data, plunge.plan(blind))
    assert found and max(f[1] for f in found) > 5
    assert not collisions(data, plunge.plan(data))
