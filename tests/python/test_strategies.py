"""Automatic plunger selection and the grid baseline, through the CLI and the module."""
import json
import subprocess

import pytest

from conftest import load_shape
from geometry_check import assert_no_gouge, coverage

SHAPE_NAMES = ["convex", "concave", "islands", "freeform", "neck"]
LIBRARY = [{"diameter": d, "id": i + 1, "feed": f}
           for i, (d, f) in enumerate([(32, 120), (25, 150), (20, 150), (16, 180), (12, 200), (8, 250), (6, 300)])]



def auto(data):
    data = dict(data)
    del data["tools"]
    data["tools"] = "auto"
    data["tool_library"] = LIBRARY
    return data


@pytest.mark.parametrize("name", ["neck", "islands"])
def test_auto_selection_cli_prints_its_reasoning(cli, tmp_path, name):
    data = auto(load_shape(name))
    src, out = tmp_path / "in.json", tmp_path / "plan.json"
    src.write_text(json.dumps(data))
    res = subprocess.run([cli, "plan", str(src), "-o", str(out), "--gcode", str(tmp_path / "p.nc")],
                         capture_output=True, text=True, timeout=600)
    assert res.returncode == 0, res.stderr
    assert "largest inscribed circle" in res.stderr and "chosen:" in res.stderr
    assert res.stdout == ""
    plan = json.loads(out.read_text())
    sel = plan["tool_selection"]
    chosen = sel["chosen"]
    # The tool that reaches all the library's smallest must cut is in every set
    # of candidates; the library as given is a set too.
    assert chosen[-1] in (sel["candidates"][-1], min(t["diameter"] for t in LIBRARY))
    assert [t["diameter"] for t in plan["stats"]["per_tool"]] == chosen
    ids = {t["diameter"]: t["id"] for t in LIBRARY}
    assert all(p["tool_id"] == ids[p["diameter"]] for p in plan["plunges"])
    assert_no_gouge(data, plan)
    # One set planned in full (the chosen one); the others placed and estimated,
    # or pruned by a bound above the best estimate.
    evaluated = [s for s in sel["sets"] if s["evaluated"]]
    assert len(evaluated) == 1 and evaluated[0]["weighted"] == pytest.approx(plan["stats"]["estimated_minutes"])
    estimated = [s for s in sel["sets"] if "plunges" in s]
    best_estimate = min(s["estimate"] if s["evaluated"] else s["weighted"] for s in estimated)
    for s in sel["sets"]:
        if "pruned" in s:
            assert s["weighted"] >= best_estimate
    # Every candidate is a library size; the G-code plunges at the library feeds.
    assert set(sel["candidates"]) <= {t["diameter"] for t in LIBRARY}
    feeds = {t["feed"] for t in LIBRARY if t["diameter"] in chosen}
    gcode = (tmp_path / "p.nc").read_text()
    assert all(("F%g" % f in gcode or "F%.1f" % f in gcode or "F%.3f" % f in gcode) for f in feeds)


def test_neck_shape_gets_a_neck_tool(plunge):
    plan = plunge.plan(auto(load_shape("neck")))
    sel = plan["tool_selection"]
    assert sel["necks"], "the neck shape's neck is found"
    width = min(n["width"] for n in sel["necks"])
    radial = load_shape("neck")["allowance"]["radial"]
    neck_tool = max(t["diameter"] for t in LIBRARY if t["diameter"] <= width - 2 * radial)
    assert neck_tool in sel["candidates"]
    assert len(sel["subregions"]) >= 2
    assert sorted(sel["subregion_order"]) == list(range(len(sel["subregions"])))


def test_auto_selection_to_stdout_is_valid_json(cli, tmp_path):
    """The default output is standard output: the plan alone, the reasoning on stderr."""
    data = auto(load_shape("neck"))
    src = tmp_path / "in.json"
    src.write_text(json.dumps(data))
    res = subprocess.run([cli, "plan", str(src)], capture_output=True, text=True, timeout=600)
    assert res.returncode == 0, res.stderr
    plan = json.loads(res.stdout)
    assert plan["tool_selection"]["chosen"] and "chosen:" in res.stderr


def test_auto_bad_input(plunge):
    data = auto(load_shape("convex"))
    with pytest.raises(ValueError, match="tool_library"):
        plunge.plan(dict(data, tool_library=[]))
    with pytest.raises(ValueError, match="tool_library"):
        plunge.plan(dict(data, tools=[{"diameter": 10}]))  # a library only with "auto"
    with pytest.raises(ValueError, match="weight"):
        plunge.plan(dict(data, selection={"weight_time": 0, "weight_tools": 0}))
    with pytest.raises(ValueError, match="time_model"):
        plunge.plan(dict(data, time_model={"rapid_rate": -1}))


@pytest.mark.parametrize("name", SHAPE_NAMES)
@pytest.mark.parametrize("pattern", ["square", "honeycomb"])
def test_grid_plans_every_shape(plunge, name, pattern):
    data = dict(load_shape(name), strategy="grid", grid={"pattern": pattern})
    plan = plunge.plan(data)
    assert plan["stats"]["plunge_count"] == len(plan["plunges"]) > 0
    assert_no_gouge(data, plan)
    measured = coverage(data, plan)
    assert measured == pytest.approx(plan["stats"]["coverage"], abs=2e-3)
    packed = plunge.plan(load_shape(name))
    # The baseline leaves pieces of the core; the packing with its 1 mm wall band none, in fewer plunges.
    assert packed["stats"]["core_coverage"] > plan["stats"]["core_coverage"]
    if pattern == "honeycomb":
        assert packed["stats"]["plunge_count"] < plan["stats"]["plunge_count"]


def test_grid_bad_input(plunge):
    data = load_shape("convex")
    with pytest.raises(ValueError, match="grid.pattern"):
        plunge.plan(dict(data, strategy="grid", grid={"pattern": "hex"}))
    with pytest.raises(ValueError, match="grid.step"):
        plunge.plan(dict(data, strategy="grid", grid={"step": 1.2}))
    with pytest.raises(ValueError, match="strategy"):
        plunge.plan(dict(data, strategy="spiral"))
