"""Sculptured floors through the CLI and the module: expression and BREP floors."""
import json
import math
import os
import shutil
import subprocess

import pytest

from conftest import SHAPES, load_shape

DATA = os.path.dirname(SHAPES)
EXPRESSION = "-25 + 4*cos(0.06*x+0.5) + 3*sin(0.08*y+1) + 6*exp(-((x-150)^2+(y-40)^2)/200)"


def floor_py(x, y):
    return (-25 + 4 * math.cos(0.06 * x + 0.5) + 3 * math.sin(0.08 * y + 1)
            + 6 * math.exp(-((x - 150) ** 2 + (y - 40) ** 2) / 200))



def disk_max(f, cx, cy, r, h=0.4):
    """The floor's maximum over the disk, sampled (a lower bound of the true one)."""
    best = -math.inf
    n = int(r / h) + 1
    for i in range(-n, n + 1):
        for j in range(-n, n + 1):
            x, y = cx + i * h, cy + j * h
            if (x - cx) ** 2 + (y - cy) ** 2 <= r * r:
                best = max(best, f(x, y))
    for k in range(360):
        t = 2 * math.pi * k / 360
        best = max(best, f(cx + r * math.cos(t), cy + r * math.sin(t)))
    return best


def test_expression_floor_depths(plunge):
    data = load_shape("islands")
    data["floor"] = {"expression": EXPRESSION}
    plan = plunge.plan(data)
    allowance = data["allowance"]["floor"]
    zs = [p["z"] for p in plan["plunges"]]
    assert max(zs) - min(zs) > 5  # the floor is not flat, nor are the stops
    for p in plan["plunges"][::3]:
        sampled = disk_max(floor_py, p["x"], p["y"], p["diameter"] / 2)
        # Never below the floor (no gouge), and not loose: sampling sees nearly the maximum.
        assert p["z"] >= sampled + allowance - 1e-6, p
        assert p["z"] <= sampled + allowance + 0.02, p


def test_ball_and_bull_tools(plunge):
    data = load_shape("convex")
    data["floor"] = {"expression": "-20 + 0.05*x"}
    data["tools"] = [{"diameter": 20, "shape": "ball"}, {"diameter": 12, "shape": "bull", "corner_radius": 2},
                     {"diameter": 6}]
    plan = plunge.plan(data)
    m = 0.05
    k = math.sqrt(1 + m * m)
    a = 0.3  # the floor allowance, kept normal to the floor: the tool grown by it drops onto the plane
    for p in plan["plunges"]:
        r = p["diameter"] / 2
        if p["tool_id"] == 1:    # ball: the analytic drop onto a plane
            expect = -20 + m * p["x"] + (r + a) * (k - 1)
        elif p["tool_id"] == 2:  # bull nose, corner radius 2
            expect = -20 + m * (p["x"] + r - 2) + (2 + a) * (k - 1)
        else:                    # flat: a bull nose of corner radius a
            expect = -20 + m * (p["x"] + r) + a * (k - 1)
        assert abs(p["z"] - (expect + a)) < 1e-6, p


def test_brep_floor_through_the_cli(cli, tmp_path):
    shutil.copy(os.path.join(DATA, "floors", "bumps.brep"), tmp_path / "bumps.brep")
    data = {"boundary": [[2, 2], [98, 2], [98, 73], [2, 73]], "islands": [[[40, 20], [55, 20], [48, 34]]],
            "tools": [{"diameter": 12}, {"diameter": 6}], "top_z": 0, "safe_z": 5,
            "floor": {"brep": "bumps.brep"}, "allowance": {"radial": 0.5, "floor": 0.3}}
    src = tmp_path / "pocket.json"
    src.write_text(json.dumps(data))
    res = subprocess.run([cli, "plan", str(src), "-o", str(tmp_path / "plan.json"), "--svg", str(tmp_path / "p.svg")],
                         capture_output=True, text=True, cwd="/")
    assert res.returncode == 0, res.stderr
    plan = json.loads((tmp_path / "plan.json").read_text())
    zs = [p["z"] for p in plan["plunges"]]
    # The face spans about -21 .. -15.5 mm; every stop is on it plus the allowance.
    assert -21.5 < min(zs) and max(zs) < -14.5 and max(zs) - min(zs) > 2
    assert plan["stats"]["core_coverage"] > 0.99999
    # The default 1 mm floor stock limit, or the warning that the 6 mm plunger cannot reach it.
    stats = plan["stats"]
    assert stats["floor_stock_plunges"] > 0
    assert stats["max_floor_stock_left"] <= 1.0 + 1e-9 or any(
        "stock stay above the floor" in w for w in plan.get("warnings", []))


def test_relative_brep_names_start_where_the_input_is(cli, plunge, tmp_path, monkeypatch):
    # One rule for every caller: the input file's folder when read from a file
    # (the CLI, whatever the current folder), the current folder for a dict.
    job = tmp_path / "job"
    job.mkdir()
    shutil.copy(os.path.join(DATA, "floors", "bumps.brep"), job / "bumps.brep")
    data = {"boundary": [[2, 2], [98, 2], [98, 73], [2, 73]], "tools": [{"diameter": 12}], "top_z": 0,
            "safe_z": 5, "floor": {"brep": "bumps.brep"}, "max_floor_stock": 0}
    (job / "pocket.json").write_text(json.dumps(data))
    res = subprocess.run([cli, "plan", "job/pocket.json", "-o", "plan.json"], capture_output=True, text=True,
                         cwd=str(tmp_path))
    assert res.returncode == 0, res.stderr
    by_cli = json.loads((tmp_path / "plan.json").read_text())["plunges"]
    monkeypatch.chdir(tmp_path)
    with pytest.raises(ValueError, match="cannot read bumps.brep"):
        plunge.plan(data)
    monkeypatch.chdir(job)
    by_module = plunge.plan(data)["plunges"]
    assert [(p["x"], p["y"], p["z"]) for p in by_module] == [(p["x"], p["y"], p["z"]) for p in by_cli]


@pytest.mark.parametrize("floor,message", [
    ({"expression": "sin(x"}, "floor.expression"),
    ({"expression": "z + 1"}, "Unexpected token"),
    ({"expression": ""}, "floor.expression is empty"),
    ({"brep": "missing.brep"}, "cannot read"),
    ({"expression": "10 + x"}, "top_z"),
    ({"z": -5, "expression": "x"}, "exactly one"),
])
def test_bad_floors(cli, tmp_path, floor, message):
    data = load_shape("convex")
    data["floor"] = floor
    src = tmp_path / "in.json"
    src.write_text(json.dumps(data))
    res = subprocess.run([cli, "plan", str(src)], capture_output=True, text=True)
    assert res.returncode == 2
    assert len(res.stderr.strip().splitlines()) == 1 and message in res.stderr
    assert res.stdout == ""


def test_optimize_standard_functions(plunge):
    him = plunge.optimize(lambda x, y: (x * x + y - 11) ** 2 + (x + y * y - 7) ** 2, [(-5, 5), (-5, 5)])
    assert him.value < 1e-10 and len([1 for x, v in him.locals if v < 1e-8]) == 4
    ros = plunge.optimize(lambda x, y: (1 - x) ** 2 + 100 * (y - x * x) ** 2, [(-2, 2), (-1, 3)], "min")
    assert abs(ros.x[0] - 1) < 1e-5 and abs(ros.x[1] - 1) < 1e-5
    ras = plunge.optimize(lambda x: 10 + x * x - 10 * math.cos(2 * math.pi * x), [(-5.12, 5.12)])
    assert abs(ras.x[0]) < 1e-6 and isinstance(ras.x, tuple) and len(ras.x) == 1
    edge = plunge.optimize(lambda x, y: x - y, [(0, 2), (0, 1)], goal="max")
    assert edge.x == pytest.approx((2, 0), abs=1e-9) and edge.value == pytest.approx(2)
    assert edge.locals[0][0] == edge.x and edge.locals[0][1] == edge.value


@pytest.mark.parametrize("bounds,message", [
    ([(1, 1)], "empty"), ([(2, 1)], "reversed"), ([], "one or two"), ([(0, 1)] * 3, "one or two"),
    ([(0, float("inf"))], "not finite"),
])
def test_optimize_bad_boxes(plunge, bounds, message):
    with pytest.raises(ValueError, match=message):
        plunge.optimize(lambda *a: 0.0, bounds)


def test_optimize_bad_functions(plunge):
    with pytest.raises(ZeroDivisionError):
        plunge.optimize(lambda x: 1 / 0, [(0, 1)])
    with pytest.raises(ValueError, match="non-finite"):
        plunge.optimize(lambda x: math.nan, [(0, 1)])
    with pytest.raises(ValueError, match="must return a float"):
        plunge.optimize(lambda x: "high", [(0, 1)])
    with pytest.raises(ValueError, match="goal"):
        plunge.optimize(lambda x: x, [(0, 1)], goal="best")


@pytest.mark.parametrize("brep", ["plane_and_sphere_blend.brep", "sphere_blend.brep"])
def test_a_small_spherical_blend_ends_with_progress_all_along(plunge, brep):
    """A public part's plateau pocket (IncludeFillets on) on a floor of its
    plane and one R1 spherical corner blend (1.3 mm2), or the blend alone: the
    floor's peak search once never returned and called no progress. Now it
    ends, here with the clear error that the pocket's outline has no floor
    under part of it (its other fillets are not in this floor), and progress
    comes all along."""
    with open(os.path.join(DATA, "floors", "plateau_input.json")) as f:
        data = json.load(f)
    data["floor"] = {"brep": os.path.join(DATA, "floors", brep)}
    stages = []
    with pytest.raises(ValueError, match="no floor under the plunge at"):
        plunge.plan(data, svg=False, progress=lambda fraction, stage: stages.append(stage) or True)
    assert "analysing the floor" in stages


def test_a_floor_no_plunger_follows_plans_within_the_step_budget(plunge):
    """The convex pocket over -25+sin(x*10): waves 0.6 mm long and 2 mm deep,
    which no plunger follows, yet too coarse to refuse. Its floor-stock step
    searched for minutes; it now stops at its budget and says so, as the
    floor stock it could not bring under the limit, and no stop is below the
    floor (sampled finely: the waves are 0.63 mm long)."""
    data = load_shape("convex")
    data["floor"] = {"expression": "-25+sin(x*10)"}
    plan = plunge.plan(data)
    said = [b for b in plan["broken_limits"] if b["limit"] == "max_floor_stock"]
    assert len(said) == 1 and "depth searches" in said[0]["why"] and said[0]["worst"] > said[0]["asked"], said
    assert any("floor-stock step stopped after" in w for w in plan["warnings"]), plan["warnings"]
    allowance = data["allowance"]["floor"]
    f = lambda x, y: -25 + math.sin(x * 10)  # noqa: E731
    for p in plan["plunges"][::4]:
        assert p["z"] >= disk_max(f, p["x"], p["y"], p["diameter"] / 2, h=0.05) + allowance - 1e-6, p
