"""The stock a plan leaves, checked independently of the planner: the wall band
and the core with shapely (GEOS, not Clipper) on random pockets, the floor stock
by dense sampling of the floor expression itself (numpy, not the planner's raster)."""
import math
import random

import numpy as np
import pytest
from shapely.geometry import Polygon

from geometry_check import accessible_and_disks, assert_no_gouge, core_left, wall_stock_left

try:  # shapely 2
    from shapely import contains_xy
except ImportError:  # shapely 1.8 (Debian 12)
    from shapely.vectorized import contains as contains_xy


def random_pocket(seed):
    """A star-shaped pocket with wavy walls, sometimes with an island, and 2-3 plungers."""
    rng = random.Random(seed)
    n = rng.randint(9, 40)
    radius = rng.uniform(45, 90)
    boundary = []
    for i in range(n):
        a = 2 * math.pi * i / n
        r = radius * rng.uniform(0.65, 1.0)
        boundary.append([round(r * math.cos(a), 4), round(0.75 * r * math.sin(a), 4)])
    islands = []
    if rng.random() < 0.5:
        c, rr = (rng.uniform(-8, 8), rng.uniform(-5, 5)), rng.uniform(6, 12)
        islands.append([[round(c[0] + rr * math.cos(-2 * math.pi * k / 24), 4),
                         round(c[1] + rr * math.sin(-2 * math.pi * k / 24), 4)] for k in range(24)])
    diameters = sorted(rng.sample([25, 20, 16, 12, 10, 8, 6], rng.randint(2, 3)), reverse=True)
    return {
        "boundary": boundary, "islands": islands,
        "tools": [{"diameter": d, "id": i + 1} for i, d in enumerate(diameters)],
        "top_z": 0, "safe_z": 5, "floor": {"z": -12},
        "allowance": {"radial": rng.choice([0.0, 0.3, 0.5]), "floor": 0.2},
        "max_wall_stock": rng.choice([0.5, 1.0, 2.0]), "seed": seed,
    }


@pytest.mark.parametrize("seed", range(8))
def test_random_pockets_cut_the_whole_core_and_leave_no_more_than_the_band(plunge, seed):
    data = random_pocket(seed)
    if not Polygon(data["boundary"], data["islands"]).is_valid:
        pytest.skip("the random walls cross")
    plan = plunge.plan(data)
    band = data["max_wall_stock"]
    assert_no_gouge(data, plan)
    left = core_left(data, plan, band)
    assert max(left, default=0.0) < 0.01, left[-5:]
    assert wall_stock_left(data, plan) <= band + 0.01
    stats = plan["stats"]
    assert stats["max_wall_stock_left"] <= band + 1e-9
    assert stats["core_coverage"] > 0.99999
    assert plunge.plan(data)["plunges"] == plan["plunges"]  # deterministic


@pytest.mark.parametrize("seed", range(3))
def test_the_band_needs_fewer_plunges_than_covering_to_a_coverage_target(plunge, seed):
    # Against the honeycomb grid see the test shapes (tests/cpp/test_plan.cpp) and
    # the README: on these jagged random pockets the grid can need fewer plunges,
    # but it leaves pieces of the core.
    data = dict(random_pocket(seed), max_wall_stock=1.0)
    if not Polygon(data["boundary"], data["islands"]).is_valid:
        pytest.skip("the random walls cross")
    plan = plunge.plan(data)
    today = plunge.plan(dict(data, max_wall_stock=0))
    grid = plunge.plan(dict(data, strategy="grid", grid={"pattern": "honeycomb"}))
    assert plan["stats"]["plunge_count"] < today["stats"]["plunge_count"]
    assert plan["stats"]["core_coverage"] > grid["stats"]["core_coverage"]


def test_zero_band_is_the_coverage_target(plunge):
    data = dict(random_pocket(3), max_wall_stock=0)
    plan = plunge.plan(data)
    stats = plan["stats"]
    assert stats["coverage"] >= 0.996 - 1e-3
    assert stats["core_coverage"] == stats["coverage"]
    assert stats["max_wall_stock_left"] > 0.0


def test_band_wider_than_the_pocket_is_refused(plunge):
    data = dict(random_pocket(1), max_wall_stock=500)
    with pytest.raises(ValueError, match="max_wall_stock"):
        plunge.plan(data)
    with pytest.raises(ValueError, match="max_floor_stock"):
        plunge.plan(dict(random_pocket(1), max_floor_stock=-1))


# Slopes up to about 0.12: a flat plunger of radius r leaves up to 2 r x slope
# on its own, so the 4 mm one can bring every step under 0.6 mm; the 10 and 20 mm
# ones cannot (steeper floors get a warning instead, see the next test).
WAVY_FLOORS = [
    ("-20 + 1.5*sin(x/12)*cos(y/15)", 0.6),
    ("-20 + 1.5*sin(x/12)*cos(y/15)", 1.0),
    ("-18 + 0.03*x + 2*exp(-((x-10)^2+(y+5)^2)/600)", 1.0),
]


def floor_stock(data, plan, step=0.25):
    """Stock above floor + allowance at every point of a fine raster of the core
    (farther than radial allowance + band from the walls, reachable by the
    smallest tool) that a plunge cuts: the lowest stop height of the flat plungers
    over it, minus the floor expression there."""
    pocket, radial, accessible, _ = accessible_and_disks(data, plan)
    core = pocket.buffer(-(radial + data.get("max_wall_stock", 1.0)), resolution=64).intersection(accessible)
    x0, y0, x1, y1 = core.bounds
    X, Y = np.meshgrid(np.arange(x0, x1, step), np.arange(y0, y1, step))
    inside = contains_xy(core, X, Y)
    cut = np.full(X.shape, np.inf)
    for p in plan["plunges"]:
        m = (X - p["x"]) ** 2 + (Y - p["y"]) ** 2 <= (p["diameter"] / 2) ** 2
        cut[m] = np.minimum(cut[m], p["z"])
    expr = data["floor"]["expression"].replace("^", "**")
    F = eval(expr, {"exp": np.exp, "sin": np.sin, "cos": np.cos, "x": X, "y": Y}) + data["allowance"]["floor"]
    keep = inside & np.isfinite(cut)
    return (cut - F)[keep]


@pytest.mark.parametrize("expression,limit", WAVY_FLOORS)
def test_no_point_of_a_sculptured_floor_keeps_more_than_the_limit(plunge, expression, limit):
    data = dict(random_pocket(5), floor={"expression": expression}, max_floor_stock=limit)
    data["tools"] = [{"diameter": 20, "id": 1}, {"diameter": 10, "id": 2}, {"diameter": 4, "id": 3}]
    plan = plunge.plan(data)
    assert_no_gouge(data, plan)
    stock = floor_stock(data, plan)
    assert stock.size > 10000
    assert stock.min() > -1e-6, "a plunge into the floor"
    assert stock.max() <= limit + 1e-6, stock.max()
    stats = plan["stats"]
    assert stats["floor_stock_plunges"] > 0 and stats["max_floor_stock_left"] <= limit
    assert stats["volume_left"] > 0 and stats["volume_removed"] > 0
    assert not any("stock stay above the floor" in w for w in plan.get("warnings", []))
    # Without the floor-stock step the steps stay: the limit is what made the difference.
    plain = plunge.plan(dict(data, max_floor_stock=0))
    assert plain["stats"]["floor_stock_plunges"] == 0
    assert floor_stock(data, plain).max() > limit


def test_a_limit_no_plunger_reaches_is_a_warning_never_a_gouge(plunge):
    # Slopes up to 0.28: the 6 mm plunger alone leaves up to 1.7 mm on them.
    data = dict(random_pocket(5), floor={"expression": "-20 + 2.5*sin(x/9)*cos(y/11)"}, max_floor_stock=1.0)
    data["tools"] = [{"diameter": 20, "id": 1}, {"diameter": 6, "id": 2}]
    plan = plunge.plan(data)
    stock = floor_stock(data, plan)
    assert stock.min() > -1e-6
    assert plan["stats"]["max_floor_stock_left"] > 1.0
    assert any("stock stay above the floor" in w for w in plan["warnings"])


def test_flat_floor_volumes_add_up(plunge):
    data = dict(random_pocket(2), max_wall_stock=1.0)
    stats = plunge.plan(data)["stats"]
    depth = data["top_z"] - (data["floor"]["z"] + data["allowance"]["floor"])
    pocket = Polygon(data["boundary"], data["islands"]).buffer(-data["allowance"]["radial"])
    # Removed + left is the pocket's volume, removed is the cut area times the depth (raster accuracy).
    assert stats["volume_removed"] + stats["volume_left"] == pytest.approx(pocket.area * depth, rel=0.02)
    assert stats["volume_removed"] == pytest.approx(stats["covered_area"] * depth, rel=0.02)
    assert stats["max_floor_stock_left"] == pytest.approx(0.0, abs=1e-9)
    assert stats["floor_stock_plunges"] == 0
