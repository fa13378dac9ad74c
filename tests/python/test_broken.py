"""Every limit the user set that a plan cannot keep is said: which, by how much,
where and why, as data ("broken_limits") and as a warning. The plan's own
claims are checked against geometry measured here (shapely), not taken as
given; the engagement, core and flute-length kinds are the C++ test
Motion.SaysEveryLimitItBreaks (plans by hand: the planner keeps those limits)."""
import math

import pytest
from shapely.geometry import Point, Polygon
from shapely.ops import unary_union

from test_schema import schema


def broken(plan, limit):
    found = [b for b in plan.get("broken_limits", []) if b["limit"] == limit]
    assert len(found) <= 1, found
    return found[0] if found else None


def said(plan, b):
    """The warning that says it: the worst, where, and why."""
    text = [w for w in plan.get("warnings", []) if b["why"] in w]
    assert len(text) == 1, plan.get("warnings")
    assert "the worst at (%.2f, %.2f)" % tuple(b["at"]) in text[0]
    return text[0]


def square(size=60, tools=(20,)):
    return {"boundary": [[0, 0], [size, 0], [size, size], [0, size]], "top_z": 0, "safe_z": 5,
            "floor": {"z": -10}, "allowance": {"radial": 0.5, "floor": 0.2}, "max_wall_stock": 1.0,
            "tools": [{"diameter": d, "id": i + 1} for i, d in enumerate(tools)]}


def test_corners_out_of_every_plungers_reach(plunge):
    """A 20 mm plunger alone leaves about 0.29 of its radius (with the allowance)
    in each square corner, more than the 1 mm band: said, at a corner, with the
    plunger that would reach it; with a 6 mm plunger too, kept and not said."""
    plan = plunge.plan(square())
    schema("plan-output.schema.json").validate({k: v for k, v in plan.items() if k != "summary"})
    b = broken(plan, "max_wall_stock")
    assert b is not None
    # The corner of the region 0.5 mm in, the disk 10 mm: 10 (1 - 1 / sqrt 2) from both walls.
    r = 10
    assert b["worst"] == pytest.approx(r * (1 - 1 / math.sqrt(2)), abs=0.15)
    assert b["asked"] == 1.0 and b["count"] >= 1
    x, y = b["at"]
    assert min(math.hypot(x - cx, y - cy) for cx in (0, 60) for cy in (0, 60)) < r  # in a corner
    # The stock measured here: the corner's point farthest from the walls that no disk covers.
    disks = unary_union([Point(p["x"], p["y"]).buffer(p["diameter"] / 2, 256) for p in plan["plunges"]])
    room = Polygon(square()["boundary"]).buffer(-0.5, join_style=2).difference(disks)
    thickest = max(min(px, py, 60 - px, 60 - py) - 0.5 for g in getattr(room, "geoms", [room])
                   for px, py in g.exterior.coords)
    assert b["worst"] == pytest.approx(thickest, abs=0.15)
    assert "a plunger of" in said(plan, b)
    kept = plunge.plan(square(tools=(20, 6)))
    assert broken(kept, "max_wall_stock") is None
    assert kept["stats"]["max_wall_stock_left"] <= 1.0 + 1e-9


def test_a_grid_short_of_the_core(plunge):
    """The grid's fixed spacing leaves core material: said where it is left."""
    data = square(tools=(12,))
    data.update(strategy="grid", grid={"pattern": "square", "step": 1.0})
    plan = plunge.plan(data)
    b = broken(plan, "max_wall_stock")
    assert b is not None and "grid" in b["why"]
    x, y = b["at"]
    disks = unary_union([Point(p["x"], p["y"]).buffer(6, 128) for p in plan["plunges"]])
    assert not disks.contains(Point(x, y))  # uncut where it says
    assert min(x, y, 60 - x, 60 - y) > 0.5 + 1.0  # and beyond the band
    said(plan, b)
    data["max_wall_stock"] = 0
    plan = plunge.plan(data)
    b = broken(plan, "min_coverage")
    assert b is not None and b["worst"] == pytest.approx(plan["stats"]["coverage"]) and b["worst"] < b["asked"]
    said(plan, b)


def test_floor_stock_no_plunger_reaches(plunge):
    """A floor with a narrow trough a 20 mm flat plunger cannot enter: the stock
    it leaves there is said, at the trough, with the tool that would."""
    data = square(tools=(20,))
    data["max_wall_stock"] = 0
    data["floor"] = {"expression": "-10 - 4*exp(-((x-30)^2)/4)"}  # a trough along x = 30
    plan = plunge.plan(data)
    b = broken(plan, "max_floor_stock")
    assert b is not None
    assert b["worst"] == pytest.approx(plan["stats"]["max_floor_stock_left"]) and b["worst"] > 1.0
    assert abs(b["at"][0] - 30) < 2  # in the trough
    assert "smaller or ball-end" in said(plan, b)


def rounded_square(size, radius, n=16):
    out = []
    for cx, cy, a0 in ((size - radius, radius, -90), (size - radius, size - radius, 0),
                       (radius, size - radius, 90), (radius, radius, 180)):
        for k in range(n + 1):
            a = math.radians(a0 + 90.0 * k / n)
            out.append([cx + radius * math.cos(a), cy + radius * math.sin(a)])
    return out


def test_the_wall_band_above_the_floor(plunge):
    """The floor's corners are round (R11, the 20 mm plunger fits them), but 5 mm
    higher the pocket's walls meet square (a section): there the corners keep
    more than the band. Said at its worst, just below that height (the pocket
    there nearly as wide as the section, cut only by the plunges to the
    floor's round corners), in a corner; the floor's own band is kept and not
    said."""
    data = square()
    data["boundary"] = rounded_square(60, 11)
    data["sections"] = [{"z": -5, "boundary": square()["boundary"]}]
    plan = plunge.plan(data)
    b = broken(plan, "max_wall_stock")
    assert b is not None and b["worst"] > 1.0
    x, y = b["at"]
    assert min(math.hypot(x - cx, y - cy) for cx in (0, 60) for cy in (0, 60)) < 10  # in a corner
    assert "just below -5.00 mm, above the floor" in said(plan, b)
    # On the diagonal the floor's plunges cut at least to the band inside the
    # arc (9.5 mm from its centre) and at most to the allowance (10.5 mm).
    assert 11 - 10.5 / math.sqrt(2) - 0.5 - 1e-6 <= b["worst"] <= 11 - 9.5 / math.sqrt(2) - 0.5 + 1e-6
    # Stops through the section's height keep its band elsewhere: the plunges of the section stop there.
    assert any(abs(p["z"] - (-5 + 0.2)) < 1e-9 for p in plan["plunges"])
    data.pop("sections")
    assert broken(plunge.plan(data), "max_wall_stock") is None
