"""Every figure of a plan's stats against an independent measurement of the
plan's own plunges: coverage and the core with shapely (GEOS, not the planner's
Clipper polygons), the wall stock from the uncovered pieces' vertices, the
floor stock and the volumes on a fine numpy raster of the floor function (not
the planner's stock samples), plunge counts by counting. Plans with a floor-stock step
in Z, engagement limits (grown plunges), levels, ball and bull tools and the grid."""
import json
import math
import os

import numpy as np
import pytest
from shapely.geometry import Polygon

from conftest import limited, load_shape
from geometry_check import _pieces, accessible_and_disks, wall_stock_left
from machine_check import floor_function, profile

try:  # shapely 2
    from shapely import contains_xy
except ImportError:  # shapely 1.8 (Debian 12)
    from shapely.vectorized import contains as contains_xy

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def example(name):
    with open(os.path.join(ROOT, "resources", "examples", name + ".json")) as f:
        return json.load(f)


def shaped(data):
    """Ball and bull-nose plungers, one with a flute length that needs levels."""
    data = json.loads(json.dumps(data))
    data["tools"] = [{"id": 1, "diameter": 16, "shape": "bull", "corner_radius": 2, "flute_length": 12},
                     {"id": 2, "diameter": 8, "shape": "ball"}]
    return data


CASES = {
    "flat example": lambda: example("pocket"),
    "sculptured example (floor-stock step)": lambda: example("sculptured"),
    "sculptured example at 0.25 D": lambda: limited(example("sculptured"), 0.25),
    "islands at 0.5 D": lambda: limited(load_shape("islands"), 0.5),
    "bull and ball with levels": lambda: shaped(example("pocket")),
    "grid": lambda: dict(load_shape("freeform"), strategy="grid"),
}


def samples(data, plan):
    """Where the planner samples the stock (stock.hpp, stockSpacing): a lattice
    over the pocket's box, about 200,000 points, at most a quarter of the
    smallest tool's radius apart and no closer than 0.2 mm, each in the middle of
    its cell. The measurement below is this test's own; only the points are the
    planner's, since the highest stock of a sculptured floor is a maximum over
    points and differs from one set of points to another."""
    x0, y0, x1, y1 = Polygon(data["boundary"]).bounds
    r_min = min(t["diameter"] for t in data["tools"]) / 2
    step = min(max(math.sqrt(plan["stats"]["region_area"] / 200000), 0.2), 0.25 * r_min)
    nx, ny = max(1, math.floor((x1 - x0) / step)), max(1, math.floor((y1 - y0) / step))
    X, Y = np.meshgrid(x0 + step / 2 + step * np.arange(nx), y0 + step / 2 + step * np.arange(ny))
    return X, Y, step


def stock_at(data, plan, X, Y):
    """At each point: the floor (+ allowance), the lowest cut surface of the
    plunges over it (inf: none), and whether it lies in the pocket (beyond the
    radial allowance) and in the core (beyond the wall band too)."""
    pocket = Polygon(data["boundary"], data.get("islands", []))
    radial = data.get("allowance", {}).get("radial", 0.0)
    band = data.get("max_wall_stock", 1.0)
    tools = {t["id"]: t for t in data["tools"]}
    cut = np.full(X.shape, np.inf)
    for p in plan["plunges"]:
        r = p["diameter"] / 2
        i0, i1 = np.searchsorted(X[0], [p["x"] - r, p["x"] + r])
        j0, j1 = np.searchsorted(Y[:, 0], [p["y"] - r, p["y"] + r])
        rho = np.hypot(X[j0:j1, i0:i1] - p["x"], Y[j0:j1, i0:i1] - p["y"])
        surface = np.where(rho <= r, p["z"] + profile(tools[p["tool_id"]], rho), np.inf)
        cut[j0:j1, i0:i1] = np.minimum(cut[j0:j1, i0:i1], surface)
    floor = floor_function(data)(X, Y) + data.get("allowance", {}).get("floor", 0.0)
    inside = contains_xy(pocket.buffer(-radial, resolution=256), X, Y)
    core = contains_xy(pocket.buffer(-(radial + band), resolution=256), X, Y) if band > 0 else inside
    return floor, cut, inside, core


@pytest.fixture(scope="module", params=list(CASES))
def planned(request, plunge):
    data = CASES[request.param]()
    return data, plunge.plan(data)



def test_counts_are_the_plunges(planned):
    data, plan = planned
    s, plunges = plan["stats"], plan["plunges"]
    assert s["plunge_count"] == len(plunges)
    per_tool = {t["tool_id"]: t["count"] for t in s["per_tool"]}
    assert per_tool == {i: sum(p["tool_id"] == i for p in plunges) for i in {p["tool_id"] for p in plunges}}
    assert s["start_holes"] == sum(bool(p.get("start_hole")) for p in plunges)
    assert s["lead_outs"] == sum("lead_out" in p for p in plunges)
    assert s["raised_lead_outs"] == sum("lead_out_z" in p for p in plunges)
    assert all("lead_out" in p and 0 < p["lead_out_z"] - p["z"] <= data.get("lead_out", 0.5) + 1e-9
               for p in plunges if "lead_out_z" in p)
    assert s["levels"] == 1 + max(p.get("level", 0) for p in plunges)
    assert s["lead_outs"] + s["no_lead_out_material"] + s["no_lead_out_walls"] == len(plunges)
    assert s["boundary_tolerance"] == 0.0  # boundaries of a few hundred vertices plan as given
    # From each lead-out's end (or the plunge) through the way's points to the next plunge.
    ways = [[a.get("lead_out", (a["x"], a["y"]))] + a.get("via", []) + [(b["x"], b["y"])]
            for a, b in zip(plunges, plunges[1:])]
    travel = sum(np.hypot(q[0] - p[0], q[1] - p[1]) for w in ways for p, q in zip(w, w[1:]))
    assert s["travel_length"] == pytest.approx(travel, rel=1e-9, abs=1e-6)


def test_coverage_is_what_the_plunges_cut(planned):
    data, plan = planned
    s = plan["stats"]
    _, _, accessible, disks = accessible_and_disks(data, plan)
    pocket, radial, _, _ = accessible_and_disks(data, plan)
    assert s["region_area"] == pytest.approx(pocket.buffer(-radial, resolution=64).area, rel=2e-3)
    assert s["accessible_area"] == pytest.approx(accessible.area, rel=2e-3)
    r_max = max(t["diameter"] for t in data["tools"]) / 2
    assert s["hex_reference_count"] == pytest.approx(accessible.area / (1.5 * math.sqrt(3) * r_max ** 2), rel=2e-3)
    assert s["covered_area"] == pytest.approx(accessible.intersection(disks).area, rel=2e-3)
    assert s["coverage"] == pytest.approx(accessible.intersection(disks).area / accessible.area, abs=1e-3)


def test_core_and_wall_stock_are_what_the_plunges_leave(planned):
    data, plan = planned
    s = plan["stats"]
    pocket, radial, accessible, disks = accessible_and_disks(data, plan)
    band = data.get("max_wall_stock", 1.0)
    core = pocket.buffer(-(radial + band), resolution=64).intersection(accessible)
    left = sum(p.area for p in _pieces(core.difference(disks)) if p.area > 1e-3)
    assert s["core_area"] == pytest.approx(core.area, rel=2e-3)
    assert s["core_coverage"] == pytest.approx(1 - left / core.area, abs=1e-3)
    # Both libraries draw disks as polygons, within a few hundredths of a mm: a
    # cusp where two arcs meet at a shallow angle moves a few times that, and a
    # pin between three disks is a little over or under the 0.01 mm^2 that counts.
    most, least = wall_stock_left(data, plan, sliver=0.005), wall_stock_left(data, plan, sliver=0.02)
    assert least - 0.06 <= s["max_wall_stock_left"] <= most + 0.06


def test_floor_stock_and_volumes_are_what_the_plunges_leave(planned):
    data, plan = planned
    s = plan["stats"]
    X, Y, step = samples(data, plan)
    floor, cut, inside, core = stock_at(data, plan, X, Y)
    top, cell = data["top_z"], step * step
    pocket_volume = np.sum(np.maximum(0.0, top - floor[inside])) * cell
    was_cut = inside & np.isfinite(cut)
    removed = np.sum(np.maximum(0.0, top - np.maximum(cut, floor))[was_cut]) * cell
    # A sample on a wall's offset may fall either side of it in the two geometries.
    edge = 2 * cell * Polygon(data["boundary"]).length * (top - np.min(floor[inside]))
    assert s["volume_removed"] == pytest.approx(removed, abs=edge)
    assert s["volume_left"] == pytest.approx(pocket_volume - removed, abs=edge)
    stock = (cut - floor)[core & np.isfinite(cut)]
    assert stock.min() > -1e-6, "a plunge into the floor"
    assert s["max_floor_stock_left"] == pytest.approx(stock.max(), abs=1e-3)
    assert s["mean_floor_stock"] == pytest.approx(stock.mean(), abs=1e-3)


def test_the_mean_floor_stock_between_the_samples(planned):
    """On a raster three times finer than the planner's samples: the same mean.
    (The highest stock is the highest at the samples: a narrow sliver of a
    shallower plunge, or a ball's rim, may rise higher between them.)"""
    data, plan = planned
    X, Y, step = samples(data, plan)
    fine = step / 3
    Xf, Yf = np.meshgrid(np.arange(X[0, 0] - step / 2, X[0, -1] + step / 2, fine),
                         np.arange(Y[0, 0] - step / 2, Y[-1, 0] + step / 2, fine))
    floor, cut, _, core = stock_at(data, plan, Xf, Yf)
    stock = (cut - floor)[core & np.isfinite(cut)]
    assert plan["stats"]["mean_floor_stock"] == pytest.approx(stock.mean(), abs=0.01)


def test_floor_stock_plunges_are_the_plunges_the_floor_stock_added(planned, plunge):
    """Without engagement limits the floor-stock step only adds: the plan without it
    has the same plunges less the floor-stock plunges (one per position with
    levels). With limits every tool grows its own plunges and none is the
    floor-stock step's. Their old key, rest_plunges, still says the same."""
    data, plan = planned
    s = plan["stats"]
    assert s["rest_plunges"] == s["floor_stock_plunges"]
    first = [p for p in plan["plunges"] if p.get("level", 0) == 0]
    if any("max_engagement" in t for t in data["tools"]):
        if all("max_engagement" in t for t in data["tools"]):
            assert s["floor_stock_plunges"] == 0
        return
    plain = plunge.plan(dict(data, max_floor_stock=0))
    assert plain["stats"]["floor_stock_plunges"] == 0
    assert len(first) == sum(p.get("level", 0) == 0 for p in plain["plunges"]) + s["floor_stock_plunges"]


def test_times_are_the_plans_moves(planned):
    """The time model (docs/plan-format.md) recomputed from the plunges' own
    heights, lead-outs and feeds: rapids across and down, feeds down and out,
    retracts, a tool change per tool."""
    data, plan = planned
    s, plunges = plan["stats"], plan["plunges"]
    feed = {t["id"]: t.get("feed", 200.0) for t in data["tools"]}
    rapid, retract, change = 10000.0, 5000.0, 20.0  # the time model's defaults
    safe = data.get("safe_z", 5.0)

    def minutes(at_safe):
        total, z = 0.0, safe
        for i, p in enumerate(plunges):
            if i > 0:
                q = plunges[i - 1]
                a = q.get("lead_out", (q["x"], q["y"]))
                for v in [] if at_safe else q.get("via", []):  # around the wall band
                    total += math.hypot(v[0] - a[0], v[1] - a[1]) / rapid
                    a = v
                total += math.hypot(p["x"] - a[0], p["y"] - a[1]) / rapid
            approach = safe if at_safe else p["approach_z"]
            up = safe if at_safe else p["retract_z"]
            total += max(0.0, z - approach) / retract + (approach - p["z"]) / feed[p["tool_id"]]
            # A pecked hole: up out of it and back to rapid_clearance above each peck.
            clearance = data.get("rapid_clearance", 1.0)
            total += sum(2 * (approach - at) - clearance for at in p.get("pecks", [])) / retract
            total += data.get("peck_dwell", 0.0) / 60.0 if p.get("pecks") else 0.0
            if "lead_out" in p:
                rise = p.get("lead_out_z", p["z"]) - p["z"]
                total += (rise + math.hypot(p["lead_out"][0] - p["x"], p["lead_out"][1] - p["y"])) / feed[p["tool_id"]]
            total += (up - p["z"]) / retract
            z = up
        changes = sum(1 for i, p in enumerate(plunges) if i == 0 or plunges[i - 1]["tool_id"] != p["tool_id"])
        return total + changes * change / 60.0

    assert s["estimated_minutes"] == pytest.approx(minutes(False), rel=1e-9)
    assert s["minutes_at_safe_height"] == pytest.approx(minutes(True), rel=1e-9)
