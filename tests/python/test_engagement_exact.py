"""Radial engagement measured exactly (engagement_check.py: polygon stock, rays
against polygon edges, independent of the planner's height field) on hand-made
cases with known answers, on the test shapes and on random pockets of varied
shapes, every tool limited to 0.25 D and 0.15 D.

The random pockets are planned and checked in a small process pool
(PLUNGE_TEST_JOBS workers, default: up to 2). The 600 x 400 mm benchmark shape
takes minutes at these limits: it runs with PLUNGE_ENGAGEMENT_BENCHMARK=1.
200 random pockets per limit with PLUNGE_LONG_TESTS=1 (CI's native run), 40 without."""
import json
import math
import os
import random
import sys
import time
from concurrent.futures import ProcessPoolExecutor
import multiprocessing

import numpy as np
import pytest
from shapely import affinity
from shapely.geometry import LineString, Point, Polygon, box
from shapely.ops import unary_union

import engagement_check as ec
from conftest import SHAPES, limited, load_shape
from test_stock import random_pocket

SLACK = 0.01        # mm: the tolerance over the limit
FRACTIONS = [0.25, 0.15]
# Random pockets per limit: 200 where PLUNGE_LONG_TESTS=1 (CI's native run,
# .ci/run), 40 elsewhere (the fresh chroots of the other FreeCAD versions).
POCKETS = 200 if os.environ.get("PLUNGE_LONG_TESTS") == "1" else 40
GROUP = 20          # pockets per test case
ACCURACY = 0.005    # mm: the checker against known answers


# ---------------------------------------------------------------------------
# (a) The checker on cases with known answers

def square_pocket(d=20.0, limit=5.0, size=100.0):
    return {"boundary": [[0, 0], [size, 0], [size, size], [0, size]], "islands": [],
            "tools": [{"diameter": d, "id": 1, "max_engagement": limit}],
            "top_z": 0, "safe_z": 5, "floor": {"z": -10}}


def plan_of(points, d=20.0, z=-10.0):
    """A hand-made plan: (x, y[, z[, start]]) per plunge, in order."""
    plunges = []
    for p in points:
        x, y = p[0], p[1]
        plunges.append({"x": x, "y": y, "diameter": d, "tool_id": 1, "z": p[2] if len(p) > 2 else z,
                        "start": bool(p[3]) if len(p) > 3 else False, "engagement": 0.0})
    return {"plunges": plunges}


def test_a_plunge_into_solid_meets_its_radius():
    res = ec.replay(square_pocket(), plan_of([(50, 50, -10, True), (20, 20)]))
    assert [q["engagement"] for q in res] == [pytest.approx(10.0, abs=1e-9)] * 2
    assert all(q["centre_in_material"] for q in res)
    assert res[0]["start"] and not res[1]["start"]
    assert [q["index"] for q in ec.over_limit(square_pocket(), plan_of([(50, 50, -10, True), (20, 20)]))] == [1]


@pytest.mark.parametrize("dx,dy", [(3.0, 0.0), (0.0, -3.0), (2.4, 1.8), (-1.2, 0.9), (0.05, 0.0)])
def test_a_crescent_measures_its_thickness(dx, dy):
    # Two disks of one radius a distance s apart: the crescent is s thick on the line of centres.
    data = square_pocket()
    res = ec.replay(data, plan_of([(50, 50, -10, True), (50 + dx, 50 + dy)]))
    assert res[1]["engagement"] == pytest.approx(math.hypot(dx, dy), abs=ACCURACY)
    assert not res[1]["centre_in_material"]
    # The thickest line points along the step.
    step = math.atan2(dy, dx) % (2 * math.pi)
    assert abs((res[1]["theta"] - step + math.pi) % (2 * math.pi) - math.pi) < 0.05


def test_a_smaller_tool_in_a_wider_hole_beside_its_rim():
    # A 12 mm disk at 6 mm from the centre of a 20 mm hole sticks out 2 mm past the rim.
    data = square_pocket()
    data["tools"].append({"diameter": 12.0, "id": 2, "max_engagement": 3.0})
    plan = plan_of([(50, 50, -10, True)])
    plan["plunges"].append({"x": 56.0, "y": 50.0, "diameter": 12.0, "tool_id": 2, "z": -10, "start": False})
    res = ec.replay(data, plan)
    assert res[1]["engagement"] == pytest.approx(2.0, abs=ACCURACY)
    assert res[1]["limit"] == 3.0


def test_a_ridge_through_the_axis_gives_the_radius():
    # Two holes 20.4 mm apart leave a waist 0.4 mm wide; the plunge on it cuts along the ridge.
    data = square_pocket()
    res = ec.replay(data, plan_of([(39.8, 50, -10, True), (60.2, 50, -10, True), (50, 50)]))
    assert res[2]["engagement"] == pytest.approx(10.0, abs=1e-9)
    # A straight ridge 0.2 mm wide and nothing else: still the whole radius.
    strip = box(-50, -0.1, 50, 0.1)
    e, theta = ec.radial_engagement(ec.edges_of(strip), 0.0, 0.0, 10.0)
    assert e == pytest.approx(10.0, abs=1e-9) and min(theta, abs(theta - math.pi)) < 1e-6
    # Off the axis by 3 mm (a 0.4 mm strip at y = -3): the longest chord inside the disk.
    strip = box(-50, -3.2, 50, -2.8)
    e, _ = ec.radial_engagement(ec.edges_of(strip), 0.0, 0.0, 10.0)
    assert e == pytest.approx(0.4 / 0.32, abs=ACCURACY)  # leaves at y = -3.2 at the rim: sin = 0.32


def test_a_thin_ridge_is_found_between_the_first_directions():
    # 0.004 mm wide, pointing 0.1 degree off any first-pass direction: the refinement finds it.
    a = math.radians(33.35)
    strip = affinity.rotate(box(0.0, -0.002, 50.0, 0.002), a, origin=(0, 0), use_radians=True)
    strip = strip.difference(Point(0, 0).buffer(2.0, 64))  # starts 2 mm out: 8 mm along it
    e, theta = ec.radial_engagement(ec.edges_of(strip), 0.0, 0.0, 10.0)
    assert e == pytest.approx(8.0, abs=ACCURACY)


def test_a_fully_cut_disk_meets_nothing():
    data = square_pocket()
    res = ec.replay(data, plan_of([(50, 50, -10, True), (50, 50)]))
    # (up to the disk polygons' chord error)
    assert res[1]["engagement"] == pytest.approx(0.0, abs=ec.CHORD) and not res[1]["centre_in_material"]
    # Inside the union of two holes: still nothing.
    data["tools"].append({"diameter": 12.0, "id": 2})
    plan = plan_of([(50, 50, -10, True), (58, 50, -10, True)])
    plan["plunges"].append({"x": 54.0, "y": 50.0, "diameter": 12.0, "tool_id": 2, "z": -10})
    assert ec.replay(data, plan)[2]["engagement"] == 0.0


def test_two_bands_each_keep_their_own_stock():
    # Level 0 stops at -5, level 1 at -10: the lower band is solid under the first hole.
    data = square_pocket()
    plan = plan_of([(50, 50, -5, True), (53, 50, -10), (50, 50, -10), (50, 53, -5)])
    res = ec.replay(data, plan)
    assert res[1]["engagement"] == pytest.approx(10.0, abs=1e-9)  # solid below -5
    assert res[2]["engagement"] == pytest.approx(3.0, abs=ACCURACY)  # crescent below, nothing above
    # The -5 plunge cuts only the upper band, where (50, 50) and (53, 50) are gone:
    # a crescent 3 mm thick along +y (the solid band below it is not its business).
    assert res[3]["engagement"] == pytest.approx(3.0, abs=ACCURACY)
    assert ec.z_bands(plan, 0.0) == [-10, -5]


def test_rays_match_shapely_on_random_stock():
    rng = np.random.default_rng(7)
    for trial in range(12):
        stock = box(-30, -30, 30, 30)
        for _ in range(10):
            stock = stock.difference(ec.disk_polygon(*rng.uniform(-14, 14, 2), rng.uniform(2, 8)))
        c = rng.uniform(-3, 3, 2)
        thetas = np.sort(rng.uniform(0, 2 * np.pi, 80))
        ours = ec.ray_lengths(ec.edges_of(stock), c[0], c[1], 10.0, thetas)
        ref = [LineString([c, c + 10 * np.array([math.cos(t), math.sin(t)])]).intersection(stock).length
               for t in thetas]
        assert np.abs(ours - ref).max() < 1e-9, trial


def test_replay_matches_a_brute_force_on_random_plunges():
    # Random plunges of two sizes into a square; the stock again with GEOS and
    # 3600 shapely rays per plunge (a lower bound: rays between them may find more).
    rng = np.random.default_rng(3)
    data = square_pocket(d=16.0, limit=4.0, size=60.0)
    data["tools"].append({"diameter": 10.0, "id": 2, "max_engagement": 2.5})
    plunges, x, y = [], 30.0, 30.0
    for i in range(14):
        d = 16.0 if i < 8 else 10.0
        if i:  # beside an earlier plunge, inside the square
            q = plunges[int(rng.integers(len(plunges)))]
            a, s = rng.uniform(0, 2 * np.pi), rng.uniform(0.2, 0.7) * d / 2
            x, y = float(np.clip(q["x"] + s * math.cos(a), 9, 51)), float(np.clip(q["y"] + s * math.sin(a), 9, 51))
        plunges.append({"x": x, "y": y, "diameter": d, "tool_id": 1 if d == 16.0 else 2, "z": -10.0,
                        "start": i == 0})
    res = ec.replay(data, {"plunges": plunges})
    assert sum(0.5 < q["engagement"] < q["r"] - 0.5 for q in res) >= 8  # mostly crescents
    stock = Polygon(data["boundary"])
    thetas = np.linspace(0, 2 * np.pi, 3600, endpoint=False)
    for i, p in enumerate(plunges):
        c, r = np.array([p["x"], p["y"]]), p["diameter"] / 2
        near = stock.intersection(Point(*c).buffer(r + 0.1, 64))
        brute = max(LineString([c, c + r * np.array([math.cos(t), math.sin(t)])]).intersection(near).length
                    for t in thetas)
        assert brute - 1e-3 <= res[i]["engagement"] <= brute + ACCURACY, (i, res[i]["engagement"], brute)
        stock = stock.difference(Point(p["x"], p["y"]).buffer(p["diameter"] / 2, 256))


def test_rays_through_vertices_and_a_centre_on_an_edge():
    for stock, c in [(box(-5, -5, 5, 5), (0, 0)), (box(0, 0, 5, 5), (0, 0)), (box(0, -5, 5, 5), (0, 0)),
                     (box(-5, -5, 5, 5), (5, 0))]:
        e, _ = ec.radial_engagement(ec.edges_of(stock), c[0], c[1], 10.0)
        ref = max(LineString([c, (c[0] + 10 * math.cos(t), c[1] + 10 * math.sin(t))]).intersection(stock).length
                  for t in np.linspace(0, 2 * np.pi, 2881))
        assert e == pytest.approx(ref, abs=1e-6)


def test_the_disk_polygon_stays_within_the_chord_tolerance():
    for r in (1.0, 2.5, 10.0, 50.0):
        disk = ec.disk_polygon(0, 0, r)
        xy = np.asarray(disk.exterior.coords)
        assert np.abs(np.hypot(xy[:, 0], xy[:, 1]) - r).max() <= ec.CHORD / 2 + 1e-12
        assert disk.exterior.distance(Point(0, 0)) >= r - ec.CHORD


# ---------------------------------------------------------------------------
# Random pockets of varied shapes

DIAMETERS = [20, 16, 12, 10, 8, 6, 5]
KINDS = ["star", "wavy", "L", "T", "dumbbell", "islands", "polygon"]


def _circle(cx, cy, r, n=32):
    """A round island, clockwise."""
    return [[round(cx + r * math.cos(-2 * math.pi * k / n), 4), round(cy + r * math.sin(-2 * math.pi * k / n), 4)]
            for k in range(n)]


def varied_pocket(seed):
    """A pocket of one of KINDS (by seed): star pockets with wavy walls (test_stock's
    random_pocket, scaled down), smooth wavy ellipses, L and T shapes, dumbbells
    with a neck, rectangles with round islands, 5- to 9-gons (heptagons most),
    some with an island; 1 to 3 plungers that fit, random allowances, wall bands
    and growth patterns. Sizes are kept to plans of about 30 to 400 plunges."""
    rng = random.Random(1000 + seed)
    kind = KINDS[seed % len(KINDS)]
    islands = []
    if kind == "star":
        for k in range(50):
            data = random_pocket(seed + 1000 * k)
            if Polygon(data["boundary"], data["islands"]).is_valid:
                break
        s = rng.uniform(0.35, 0.5)
        boundary = [[round(x * s, 4), round(y * s, 4)] for x, y in data["boundary"]]
        islands = [[[round(x * s, 4), round(y * s, 4)] for x, y in loop] for loop in data["islands"]]
        size = 2 * s * 45
    else:
        if kind == "wavy":
            radius, k, a, phase = rng.uniform(22, 38), rng.randint(3, 7), rng.uniform(0.08, 0.22), rng.uniform(0, 6.3)
            ts = [2 * math.pi * i / 120 for i in range(120)]
            poly = Polygon([(radius * (1 + a * math.sin(k * t + phase)) * math.cos(t),
                             0.8 * radius * (1 + a * math.sin(k * t + phase)) * math.sin(t)) for t in ts])
            size = 1.4 * radius * (1 - a)
        elif kind == "L":
            w1, w2, l1, l2 = rng.uniform(18, 30), rng.uniform(18, 30), rng.uniform(45, 75), rng.uniform(40, 65)
            poly = box(0, 0, l1, w1).union(box(0, 0, w2, l2))
            size = min(w1, w2)
        elif kind == "T":
            w1, w2, l1, l2 = rng.uniform(18, 28), rng.uniform(16, 26), rng.uniform(55, 80), rng.uniform(35, 55)
            poly = box(-l1 / 2, 0, l1 / 2, w1).union(box(-w2 / 2, -l2, w2 / 2, 0.0001))
            size = min(w1, w2)
        elif kind == "dumbbell":
            radius, gap = rng.uniform(14, 22), rng.uniform(10, 25)
            neck = rng.uniform(0.35, 0.7) * radius
            c = radius + gap / 2
            poly = unary_union([Point(-c, 0).buffer(radius, 32), Point(c, 0).buffer(radius, 32),
                                box(-c, -neck / 2, c, neck / 2)])
            size = 2 * radius
        elif kind == "islands":
            w, h = rng.uniform(55, 85), rng.uniform(40, 60)
            poly = box(0, 0, w, h)
            size = min(w, h)
            placed = []
            for _ in range(rng.randint(1, 3)):
                for _try in range(30):
                    r = rng.uniform(3, 8)
                    x, y = rng.uniform(r + 8, w - r - 8), rng.uniform(r + 8, h - r - 8)
                    if all(math.hypot(x - a, y - b) > r + q + 8 for a, b, q in placed):
                        placed.append((x, y, r))
                        break
            islands = [_circle(0.8 * x, 0.8 * y, 0.8 * r) for x, y, r in placed]
        else:  # polygon: 5 to 9 sides, sometimes a round island
            n, radius, rot = rng.choice([5, 6, 7, 7, 7, 8, 9]), rng.uniform(25, 40), rng.uniform(0, 6.3)
            poly = Polygon([(radius * math.cos(rot + 2 * math.pi * i / n), radius * math.sin(rot + 2 * math.pi * i / n))
                            for i in range(n)])
            size = 2 * radius * math.cos(math.pi / n)
            if rng.random() < 0.5:
                islands = [_circle(rng.uniform(-2.4, 2.4), rng.uniform(-2.4, 2.4), rng.uniform(2.4, 4.8))]
        if kind != "islands":
            poly = affinity.rotate(poly, rng.uniform(0, 360), origin=(0, 0))
        poly = affinity.scale(poly, 0.8, 0.8, origin=(0, 0))
        size *= 0.8
        boundary = [[round(x, 4), round(y, 4)] for x, y in list(poly.exterior.coords)[:-1]]
    fits = [d for d in DIAMETERS if d <= 0.55 * size]
    big = rng.choice(fits[:3])
    rest = [d for d in fits if d <= 0.8 * big]
    diameters = [big] + sorted(rng.sample(rest, min(len(rest), rng.randint(1, 2))), reverse=True)
    return {
        "boundary": boundary, "islands": islands,
        "tools": [{"diameter": d, "id": i + 1} for i, d in enumerate(diameters)],
        "top_z": 0, "safe_z": 5, "floor": {"z": -12},
        "allowance": {"radial": rng.choice([0.0, 0.3, 0.5]), "floor": 0.2},
        "max_wall_stock": rng.choice([0.5, 1.0, 2.0]), "seed": seed,
        "growth_pattern": rng.choice(["auto", "rows", "offsets"]),
    }


def checked(plunge, data, name):
    """Plan and replay: a short record of the violations and the times."""
    t0 = time.process_time()
    plan = plunge.plan(data)
    t1 = time.process_time()
    results = ec.replay(data, plan)
    t2 = time.process_time()
    over = ec.over_limit(data, plan, SLACK, results)
    return {
        "name": name, "plunges": len(results), "starts": sum(q["start"] for q in results),
        "over": len(over), "max_excess": max([q["engagement"] - q["limit"] for q in over], default=0.0),
        "worst": [{k: (round(v, 4) if isinstance(v, float) else v) for k, v in q.items()}
                  for q in sorted(over, key=lambda q: q["limit"] - q["engagement"])[:3]],
        "plan_seconds": t1 - t0, "check_seconds": t2 - t1,
    }


_WORKER_PLUNGE = None


def _init_worker(paths):
    global _WORKER_PLUNGE
    for p in paths:
        if p not in sys.path:
            sys.path.insert(0, p)
    import plunge as module
    _WORKER_PLUNGE = module


def _check_random(args):
    seed, fraction = args
    return checked(_WORKER_PLUNGE, limited(varied_pocket(seed), fraction), "pocket %d (%s)" % (seed, KINDS[seed % 7]))


@pytest.fixture(scope="module")
def pool(plunge):
    jobs = int(os.environ.get("PLUNGE_TEST_JOBS", min(2, os.cpu_count() or 1)))
    if jobs <= 1:
        yield None
        return
    paths = [os.path.dirname(plunge.__file__), os.path.dirname(os.path.abspath(__file__))]
    with ProcessPoolExecutor(jobs, mp_context=multiprocessing.get_context("spawn"),
                             initializer=_init_worker, initargs=(paths,)) as executor:
        yield executor


def describe(failures):
    return "\n".join("%s: %d plunges over the limit, worst +%.3f mm: %s"
                     % (f["name"], f["over"], f["max_excess"], f["worst"]) for f in failures)


def test_the_random_pockets_are_valid_and_varied():
    kinds = set()
    for seed in range(0, POCKETS, 3):
        data = varied_pocket(seed)
        assert Polygon(data["boundary"], data["islands"]).is_valid, seed
        kinds.add(KINDS[seed % 7])
    assert kinds == set(KINDS)


@pytest.mark.parametrize("fraction", FRACTIONS)
@pytest.mark.parametrize("group", range(POCKETS // GROUP))
def test_random_pockets_keep_the_limit_exactly(plunge, pool, fraction, group):
    seeds = range(group * GROUP, (group + 1) * GROUP)
    if pool is None:
        reports = [checked(plunge, limited(varied_pocket(s), fraction), "pocket %d (%s)" % (s, KINDS[s % 7]))
                   for s in seeds]
    else:
        reports = list(pool.map(_check_random, [(s, fraction) for s in seeds]))
    failures = [r for r in reports if r["over"]]
    assert not failures, "%d of %d pockets at %.2f D:\n%s" % (len(failures), len(reports), fraction, describe(failures))


SHAPE_NAMES = sorted(f[:-5] for f in os.listdir(SHAPES) if f.endswith(".json"))
BENCHMARK = bool(os.environ.get("PLUNGE_ENGAGEMENT_BENCHMARK"))


def _check_shape(args):
    name, fraction = args
    return checked(_WORKER_PLUNGE, limited(load_shape(name), fraction), name)


@pytest.fixture(scope="module")
def shape_jobs(pool, request):
    """Every selected shape case submitted to the pool at once, so they run side by side."""
    jobs = {}
    if pool is not None:
        for item in request.session.items:
            spec = getattr(item, "callspec", None)
            if getattr(item, "originalname", None) == "test_shapes_keep_the_limit_exactly" and spec is not None:
                key = (spec.params["name"], spec.params["fraction"])
                if key[0] != "benchmark" or BENCHMARK:
                    jobs[key] = pool.submit(_check_shape, key)
    return jobs


@pytest.mark.parametrize("fraction", FRACTIONS)
@pytest.mark.parametrize("name", SHAPE_NAMES)
def test_shapes_keep_the_limit_exactly(plunge, shape_jobs, name, fraction):
    if name == "benchmark" and not BENCHMARK:
        pytest.skip("minutes at these limits: PLUNGE_ENGAGEMENT_BENCHMARK=1 runs it")
    if (name, fraction) in shape_jobs:
        report = shape_jobs[(name, fraction)].result()
    else:
        report = checked(plunge, limited(load_shape(name), fraction), name)
    assert report["over"] == 0, describe([report])


@pytest.mark.parametrize("seed", [0, 3])
def test_levels_keep_the_limit_exactly(plunge, seed):
    # Short flutes: three levels (one stock per z band), each plunge against the bands it cuts.
    data = limited(varied_pocket(seed), 0.25)
    for t in data["tools"]:
        t["flute_length"] = 5.0
    plan = plunge.plan(data)
    assert len(ec.z_bands(plan, data["top_z"])) == 3
    over = ec.over_limit(data, plan, SLACK)
    assert not over, over[:3]
