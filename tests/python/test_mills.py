"""Real plunge mills: plans posted as G-code by the command-line tool, run
through the G-code checker (machine_check.py: a simulated stock independent of
the planner) on random pockets and the bundled examples."""
import json
import math
import os
import subprocess

import pytest
from shapely.geometry import Polygon

from geometry_check import assert_no_gouge, core_left
from machine_check import assert_machinable, check_program
from test_stock import random_pocket

EXAMPLES = os.path.join(os.path.dirname(__file__), "..", "..", "resources", "examples")


def mill(data, kind):
    """The pocket's tools as real plunge mills of one kind."""
    data = json.loads(json.dumps(data))
    tools = data["tools"]
    largest = max(t["diameter"] for t in tools)
    for t in tools:
        d = t["diameter"]
        if kind == "half":
            t["max_engagement"] = 0.5 * d
        elif kind == "quarter":
            t["max_engagement"] = 0.25 * d
            t["min_engagement"] = 0.05 * d
        elif kind == "plunge_cutter" and d == largest:  # indexable: a core, a band, a sweet spot
            t.update(center_cutting=False, core_diameter=0.3 * d, max_engagement=0.5 * d, min_engagement=0.1 * d)
        elif kind == "short_flutes":
            t["flute_length"] = 5.0
    return data


FRACTION = {"half": 0.5, "quarter": 0.25}  # mill()'s limits, as a share of the diameter


def row_bound(data, free, stats, kind):
    """The issue's bound: rows 0.87 D apart, a plunge every e along them
    (area / (0.87 D e) for the largest tool), or the unlimited plan where that
    is more."""
    largest = max(t["diameter"] for t in data["tools"])
    return max(free["stats"]["plunge_count"], stats["region_area"] / (0.87 * largest * FRACTION[kind] * largest))


def post(cli, data, tmp_path):
    src = tmp_path / "in.json"
    src.write_text(json.dumps(data))
    out, nc = tmp_path / "plan.json", tmp_path / "plan.nc"
    run = subprocess.run([cli, "plan", str(src), "-o", str(out), "--gcode", str(nc)], capture_output=True, text=True,
                         timeout=300)
    assert run.returncode == 0, run.stderr
    return json.loads(out.read_text()), nc.read_text()


@pytest.mark.parametrize("kind", ["half", "quarter", "plunge_cutter", "short_flutes"])
@pytest.mark.parametrize("seed", range(3))
def test_random_pockets_pass_the_checker(cli, tmp_path, seed, kind):
    data = mill(random_pocket(seed), kind)
    if not Polygon(data["boundary"], data["islands"]).is_valid:
        pytest.skip("the random walls cross")
    plan, gcode = post(cli, data, tmp_path)
    report = check_program(data, data["tools"], gcode)
    # Flat floors: every limit kept, no gouge, no rapid through stock.
    assert_machinable(report)
    stats = plan["stats"]
    assert stats["over_engaged"] == 0
    assert report["plunges"] == stats["plunge_count"] == len(plan["plunges"])
    assert report["lead_outs"] == sum("lead_out" in p for p in plan["plunges"]) > 0
    # Thin cuts are never hidden (the two rasters count them differently near the limit).
    if report["thin"]:
        assert stats["thin_cuts"] > 0 and any("min engagement" in w for w in plan["warnings"])
    assert_no_gouge(data, plan)
    # Growing within the limits still cuts the core (slivers under 0.5 mm^2 aside).
    assert sum(core_left(data, plan, data["max_wall_stock"])) < 0.5
    if kind == "plunge_cutter":
        assert stats["start_holes"] >= 1
        holes = [p for p in plan["plunges"] if p["start_hole"]]
        assert plan["plunges"][:len(holes)] == holes  # drilled first
        assert all(p["diameter"] >= 0.3 * max(t["diameter"] for t in data["tools"]) for p in holes)
    if kind == "short_flutes":
        assert stats["levels"] == 3  # 12 mm (less the floor allowance) in 5 mm levels
    for k in ("half", "quarter"):
        if kind == k:
            fraction = FRACTION[k]
            for t in data["tools"]:
                measured = report["max_engagement"].get(t["id"], 0.0)
                assert measured <= fraction * t["diameter"] + 1.5 * 0.5, (t, measured)


def test_limits_cost_plunges_and_stock_aware_heights_save_time(cli, tmp_path):
    data = json.load(open(os.path.join(EXAMPLES, "pocket.json")))
    free, _ = post(cli, data, tmp_path)
    half, _ = post(cli, mill(data, "half"), tmp_path)
    quarter, _ = post(cli, mill(data, "quarter"), tmp_path)
    assert free["stats"]["plunge_count"] < half["stats"]["plunge_count"] < quarter["stats"]["plunge_count"]
    for plan in (free, half, quarter):
        s = plan["stats"]
        assert s["estimated_minutes"] < s["minutes_at_safe_height"]
    at_safe, _ = post(cli, dict(data, stock_aware_heights=False), tmp_path)
    assert all(p["approach_z"] == data["safe_z"] and p["retract_z"] == data["safe_z"] for p in at_safe["plunges"])
    assert abs(at_safe["stats"]["estimated_minutes"] - at_safe["stats"]["minutes_at_safe_height"]) < 1e-9


def test_sculptured_example_with_a_plunge_cutter(cli, tmp_path):
    data = mill(json.load(open(os.path.join(EXAMPLES, "sculptured.json"))), "plunge_cutter")
    plan, gcode = post(cli, data, tmp_path)
    report = check_program(data, data["tools"], gcode)
    # No gouge (walls, floor, lead-outs) and no rapid through stock, as on flat floors.
    for key in ("gouges", "rapid_through_stock", "lead_out_into_material", "too_deep"):
        assert not report[key], (key, report[key][:3])
    # Over a sculptured floor uneven depths can leave thick steps: the few plunges
    # that meet more than their limit there are the plan's own warnings (within
    # the rasters' difference).
    assert len(report["over_engaged"]) <= plan["stats"]["over_engaged"] + 3
    assert len(report["core_on_material"]) <= 5
    assert plan["stats"]["start_holes"] >= 1


@pytest.mark.parametrize("kind", ["half", "quarter"])
def test_sculptured_limited_plans_lead_out_raised_out_of_the_steps(cli, tmp_path, kind):
    """Over a sculptured floor plunges stop at different heights: one deeper than
    those around sits in a ring of their steps. It feeds up out of them (no
    more than the lead-out is long) and then leads out, so nearly every plunge
    does; the checker replays each raised lead-out at its height. The tour,
    shortened within the order the growth allows, travels at most 1.5 times
    as far per plunge as the unlimited plan's. The plunges stay within 1.3
    times the row bound or the unlimited plan (its floor-stock plunges in Z count),
    and leave no more stock on the floor than the unlimited plan."""
    free, _ = post(cli, json.load(open(os.path.join(EXAMPLES, "sculptured.json"))), tmp_path)
    data = mill(json.load(open(os.path.join(EXAMPLES, "sculptured.json"))), kind)
    plan, gcode = post(cli, data, tmp_path)
    stats, plunges = plan["stats"], plan["plunges"]
    bound = row_bound(data, free, stats, kind)
    assert stats["plunge_count"] <= 1.3 * bound, (stats["plunge_count"], bound)
    assert stats["max_floor_stock_left"] <= free["stats"]["max_floor_stock_left"] + 1e-6
    per_plunge = stats["travel_length"] / (len(plunges) - 1)
    free_per_plunge = free["stats"]["travel_length"] / (free["stats"]["plunge_count"] - 1)
    assert per_plunge <= 1.5 * free_per_plunge, (per_plunge, free_per_plunge)
    raised = [p for p in plunges if "lead_out_z" in p]
    assert stats["raised_lead_outs"] == len(raised) > 0
    assert all(0 < p["lead_out_z"] - p["z"] <= data.get("lead_out", 0.5) for p in raised)
    # (0.88 at 0.5 D since the floor allowance is kept normal to the floor: on
    # slopes the stops are higher, and more plunges sit in steps deeper than
    # the lead-out is long, 0.91 before.)
    assert stats["lead_outs"] >= 0.85 * len(plunges), (stats["lead_outs"], len(plunges))
    report = check_program(data, data["tools"], gcode)
    assert report["lead_outs"] == stats["lead_outs"]
    for key in ("gouges", "rapid_through_stock", "lead_out_into_material", "too_deep"):
        assert not report[key], (key, report[key][:3])
    # Uneven depths leave steps: what the checker finds over the limit, the plan
    # counts and warns of too (a raster's difference aside).
    assert len(report["over_engaged"]) <= stats["over_engaged"] + 1, (report["over_engaged"], stats["over_engaged"])


def ring_pocket():
    """A round pocket 120 mm across around a round island 50 mm across, over a
    wavy floor (like the FreeCAD demo's): the wall's contour and the island's
    lie less than two swaths of the 20 mm tool apart."""
    def circle(r, n):
        return [[r * math.cos(2 * math.pi * i / n), r * math.sin(2 * math.pi * i / n)] for i in range(n)]
    return {"version": 1, "boundary": circle(60.0, 120), "islands": [circle(25.0, 60)[::-1]],
            "tools": [{"diameter": 20.0, "id": 1}, {"diameter": 12.0, "id": 2}, {"diameter": 6.0, "id": 3}],
            "top_z": 0.0, "safe_z": 5.0, "floor": {"expression": "-25 + 2*sin(x/15)*cos(y/15)"},
            "allowance": {"radial": 0.5, "floor": 0.3}, "max_wall_stock": 1.0, "max_floor_stock": 1.0}


@pytest.mark.parametrize("kind", ["half", "quarter"])
def test_rows_between_the_wall_and_an_island_are_not_cut_twice(cli, tmp_path, kind):
    """The contours of the wall and of the island cut the whole ring between
    them; a row there would cut it again. Walks along the contours stop at
    deeper neighbours over a wavy floor, and rows were entered first: 1.24 x
    the bound at 0.25 D. Rows are now left out where the contours cut, within
    1.2 x, and the plan still passes the checker."""
    free, _ = post(cli, ring_pocket(), tmp_path)
    data = ring_pocket()
    for t in data["tools"]:  # the limit alone (mill() adds a min_engagement at 0.25 D)
        t["max_engagement"] = FRACTION[kind] * t["diameter"]
    plan, gcode = post(cli, data, tmp_path)
    stats = plan["stats"]
    bound = row_bound(data, free, stats, kind)
    assert stats["plunge_count"] <= 1.2 * bound, (stats["plunge_count"], bound)
    report = check_program(data, data["tools"], gcode)
    for key in ("gouges", "rapid_through_stock", "lead_out_into_material", "too_deep"):
        assert not report[key], (key, report[key][:3])
    assert len(report["over_engaged"]) <= stats["over_engaged"] + 1, (report["over_engaged"], stats["over_engaged"])
    assert_no_gouge(data, plan)


def test_lead_out_zero_retracts_straight_up(cli, tmp_path):
    data = json.load(open(os.path.join(EXAMPLES, "pocket.json")))
    plan, gcode = post(cli, dict(data, lead_out=0), tmp_path)
    assert not any("lead_out" in p for p in plan["plunges"])
    assert not [line for line in gcode.splitlines() if line.startswith("G1 X")]


@pytest.mark.parametrize("tool, message", [
    ({"diameter": 20, "center_cutting": False}, "core_diameter"),
    ({"diameter": 20, "center_cutting": False, "core_diameter": 25}, "below 90 %"),
    ({"diameter": 20, "core_diameter": 6}, "do not cut at the centre"),
    ({"diameter": 20, "max_engagement": 0.5}, "below 5 % of the diameter"),
    ({"diameter": 20, "max_engagement": 5, "min_engagement": 8}, "above its max_engagement"),
    ({"diameter": 20, "max_engagement": -1}, "must be > 0"),
    ({"diameter": 20, "shape": "ball", "flute_length": 10}, "flute_length must exceed the corner radius"),
    ({"diameter": 20, "center_cutting": "no"}, "expected true or false"),
])
def test_bad_mills_are_refused(cli, tmp_path, tool, message):
    data = {"boundary": [[0, 0], [120, 0], [120, 80], [0, 80]], "tools": [tool], "floor": {"z": -10}}
    src = tmp_path / "in.json"
    src.write_text(json.dumps(data))
    run = subprocess.run([cli, "plan", str(src)], capture_output=True, text=True, timeout=60)
    assert run.returncode == 2 and message in run.stderr and len(run.stderr.splitlines()) == 1, run.stderr


def test_a_plunge_cutter_needs_a_centre_cutting_tool_for_its_start_holes(cli, tmp_path):
    data = {"boundary": [[0, 0], [120, 0], [120, 80], [0, 80]], "floor": {"z": -10},
            "tools": [{"diameter": 25, "center_cutting": False, "core_diameter": 10}, {"diameter": 8}]}
    src = tmp_path / "in.json"
    src.write_text(json.dumps(data))
    run = subprocess.run([cli, "plan", str(src)], capture_output=True, text=True, timeout=60)
    assert run.returncode == 2
    assert "does not cut at its centre" in run.stderr and "at least 10 mm wide" in run.stderr


SHAPES = os.path.join(os.path.dirname(__file__), "..", "data", "shapes")


@pytest.mark.parametrize("shape", ["convex", "concave", "islands", "freeform", "neck"])
def test_limited_plans_stay_near_the_row_bound_travel_little_and_lead_out(cli, tmp_path, shape):
    """A band limit e costs about area / (0.87 D e) plunges (rows 0.87 D apart,
    a plunge every e along them): the plan stays within 1.3 times that (or of
    the unlimited plan, where that is more), travels at most 1.5 times as far
    per plunge as the unlimited plan, and nearly every plunge leads out."""
    data = json.load(open(os.path.join(SHAPES, shape + ".json")))
    free, _ = post(cli, data, tmp_path)
    for kind in ("half", "quarter"):
        plan, _ = post(cli, mill(data, kind), tmp_path)
        stats = plan["stats"]
        bound = row_bound(data, free, stats, kind)
        assert stats["plunge_count"] <= 1.3 * bound, (kind, stats["plunge_count"], bound)
        # The tour: rows walked in turn, one piece of the region after another.
        per_plunge = stats["travel_length"] / (stats["plunge_count"] - 1)
        free_per_plunge = free["stats"]["travel_length"] / (free["stats"]["plunge_count"] - 1)
        assert per_plunge <= 1.5 * free_per_plunge, (kind, per_plunge, free_per_plunge)
        plunges = plan["plunges"]
        with_lead_out = sum("lead_out" in p for p in plunges)
        assert with_lead_out == stats["lead_outs"]
        assert with_lead_out >= 0.9 * len(plunges), (kind, with_lead_out, len(plunges))
        # The others are counted by reason.
        assert stats["no_lead_out_material"] + stats["no_lead_out_walls"] == len(plunges) - with_lead_out


def test_offsets_of_the_contour_where_they_cost_fewer_plunges(cli, tmp_path):
    """A dumbbell's lobes are round: offsets of their contour follow them,
    where rows cross them and end at the walls. With growth_pattern "auto" (the
    default) each limited tool is grown both ways and keeps the cheaper; on the
    neck shape at 0.25 D that is offsets: within 1.1 x the bound (1.17 x with
    rows). A plan along offsets only passes the G-code checker too, and a
    pattern the planner does not know is refused, naming the ones it does."""
    data = json.load(open(os.path.join(SHAPES, "neck.json")))
    free, _ = post(cli, data, tmp_path)
    plans = {}
    for pattern in ("rows", "offsets", "auto"):
        limited = dict(mill(data, "quarter"), growth_pattern=pattern)
        plans[pattern], gcode = post(cli, limited, tmp_path)
        if pattern == "offsets":
            report = check_program(limited, limited["tools"], gcode)
            for key in ("gouges", "rapid_through_stock", "lead_out_into_material", "too_deep"):
                assert not report[key], (key, report[key][:3])
            assert_no_gouge(limited, plans[pattern])
    count = {k: p["stats"]["plunge_count"] for k, p in plans.items()}
    bound = row_bound(data, free, plans["auto"]["stats"], "quarter")
    assert count["auto"] <= 1.1 * bound, (count, bound)
    assert count["auto"] < count["rows"], count
    assert plans["auto"]["stats"]["core_coverage"] > 0.9999
    src = tmp_path / "bad.json"
    src.write_text(json.dumps(dict(data, growth_pattern="spiral")))
    run = subprocess.run([cli, "plan", str(src)], capture_output=True, text=True, timeout=60)
    assert run.returncode == 2 and "growth_pattern: unknown pattern 'spiral'" in run.stderr, run.stderr
