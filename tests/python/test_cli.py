"""The command-line tool on every test shape, and on bad input."""
import json
import math
import subprocess
import xml.etree.ElementTree as ET

import pytest

from conftest import load_shape
from geometry_check import assert_no_gouge, core_left, coverage, wall_stock_left

SHAPE_NAMES = ["convex", "concave", "islands", "freeform", "neck"]



def run(cli, data, tmp_path, *extra):
    src = tmp_path / "in.json"
    src.write_text(json.dumps(data) if not isinstance(data, str) else data)
    return subprocess.run([cli, "plan", str(src), *extra], capture_output=True, text=True, timeout=120)


@pytest.mark.parametrize("name", SHAPE_NAMES)
def test_plans_every_shape(cli, tmp_path, name):
    data = load_shape(name)
    out, svg, nc = tmp_path / "plan.json", tmp_path / "plan.svg", tmp_path / "plan.nc"
    res = run(cli, data, tmp_path, "-o", str(out), "--svg", str(svg), "--gcode", str(nc))
    assert res.returncode == 0, res.stderr
    # Standard error: the one-line summary with the stock left, no warning.
    lines = res.stderr.splitlines()
    assert len(lines) == 1 and lines[0].startswith("plunge-rough: ") and "stock left: walls up to" in lines[0], lines
    plan = json.loads(out.read_text())
    stats = plan["stats"]
    assert stats["plunge_count"] == len(plan["plunges"]) > 0
    assert sum(t["count"] for t in stats["per_tool"]) == stats["plunge_count"]
    assert_no_gouge(data, plan)
    measured = coverage(data, plan)
    assert abs(measured - stats["coverage"]) < 2e-3
    # The default 1 mm wall band, measured with GEOS: the core cut whole, no thicker stock on the walls.
    assert max(core_left(data, plan, 1.0), default=0.0) < 0.01
    assert wall_stock_left(data, plan) <= 1.0 + 0.01
    assert stats["max_wall_stock_left"] <= 1.0 + 1e-9 and stats["core_coverage"] > 0.99999
    # Tools from the largest down, each tool's plunges together.
    diameters = [p["diameter"] for p in plan["plunges"]]
    assert diameters == sorted(diameters, reverse=True)
    floor = data["floor"]["z"] + data["allowance"]["floor"]
    assert all(abs(p["z"] - floor) < 1e-9 for p in plan["plunges"])
    # The plan's picture: one circle per plunge, plus a legend swatch and a
    # first-plunge ring per tool; the stock left beside it, each plunge's disk
    # outlined there; no stop heights over a flat floor.
    root = ET.parse(svg).getroot()
    circles = root.findall("{http://www.w3.org/2000/svg}circle")
    assert len(circles) == len(plan["plunges"]) + 2 * len(stats["per_tool"])
    stock = ET.parse(tmp_path / "plan-stock.svg").getroot()
    assert len(stock.findall("{http://www.w3.org/2000/svg}circle")) == len(plan["plunges"])
    assert not (tmp_path / "plan-heights.svg").exists()
    # The G-code: one feed move down per plunge and per peck, one across per lead-out.
    feeds = [line for line in nc.read_text().splitlines() if line.startswith("G1 ")]
    assert len([f for f in feeds if " Z" in f]) == len(plan["plunges"]) + sum(len(p.get("pecks", []))
                                                                            for p in plan["plunges"])
    assert len([f for f in feeds if " Z" not in f]) == len([p for p in plan["plunges"] if "lead_out" in p])


def test_tool_paths_start_where_they_should(cli, tmp_path):
    data = load_shape("islands")
    data["start"] = [200, 120]
    plan = json.loads(run(cli, data, tmp_path).stdout)
    plunges = plan["plunges"]
    first_tool = [p for p in plunges if p["tool_id"] == plunges[0]["tool_id"]]
    nearest = min(first_tool, key=lambda p: math.dist((p["x"], p["y"]), (200, 120)))
    assert plunges[0] == nearest
    # Each later tool starts at its plunge nearest to where the previous tool ended.
    for i in range(1, len(plunges)):
        if plunges[i]["tool_id"] != plunges[i - 1]["tool_id"]:
            same = [p for p in plunges if p["tool_id"] == plunges[i]["tool_id"]]
            end = (plunges[i - 1]["x"], plunges[i - 1]["y"])
            assert plunges[i] == min(same, key=lambda p: math.dist((p["x"], p["y"]), end))
    # Travel from each lead-out's end (or the plunge) to the next plunge.
    travel = sum(math.dist(plunges[i - 1].get("lead_out", (plunges[i - 1]["x"], plunges[i - 1]["y"])),
                           (plunges[i]["x"], plunges[i]["y"])) for i in range(1, len(plunges)))
    assert abs(travel - plan["stats"]["travel_length"]) < 1e-6


def test_stdout_is_the_default_output(cli, tmp_path):
    res = run(cli, load_shape("convex"), tmp_path)
    assert res.returncode == 0
    assert json.loads(res.stdout)["stats"]["plunge_count"] > 0


def test_automatic_tools_on_stdout_give_valid_json(cli, tmp_path):
    # The tool choice's reasoning goes to standard error: standard output stays the plan.
    data = load_shape("neck")
    data["tool_library"] = [{"diameter": d} for d in (20, 16, 12, 8, 6)]
    data["tools"] = "auto"
    res = run(cli, data, tmp_path)
    assert res.returncode == 0, res.stderr
    plan = json.loads(res.stdout)  # the whole of it: "Extra data" after the plan fails here
    reasoning = plan["tool_selection"]["reasoning"]
    assert plan["stats"]["plunge_count"] == len(plan["plunges"]) > 0 and reasoning
    assert all(line in res.stderr.splitlines() for line in reasoning)


def test_same_input_same_plan(cli, tmp_path):
    a = json.loads(run(cli, load_shape("islands"), tmp_path).stdout)
    b = json.loads(run(cli, load_shape("islands"), tmp_path).stdout)
    assert a["plunges"] == b["plunges"]


def mutate(path, value):
    data = load_shape("islands")
    node = data
    for key in path[:-1]:
        node = node[key]
    if value is KeyError:
        del node[path[-1]]
    else:
        node[path[-1]] = value
    return data


BAD = [
    ("not json", "invalid JSON"),
    (mutate(["boundary"], [[0, 0], [1, 0]]), "at least 3 distinct points"),
    (mutate(["boundary"], [[0, 0], [10, 0], [20, 0]]), "zero area"),
    (mutate(["boundary"], [[0, 0], [200, 0], [200, 120], [100, -50], [0, 120]]), "self-intersecting"),
    (mutate(["islands"], [[[300, 300], [310, 300], [305, 310]]]), "outside the boundary"),
    (mutate(["islands"], [[[190, 50], [230, 50], [210, 70]]]), "crosses"),
    (mutate(["islands"], [[[40, 30], [80, 30], [60, 80]], [[[50, 40], [70, 40], [60, 60]]][0]]), "overlap"),
    (mutate(["tools"], [{"diameter": -6}]), "diameter must be > 0"),
    (mutate(["tools"], [{"diameter": 0}]), "diameter must be > 0"),
    (mutate(["tools"], [{"diameter": 500}]), "no tool fits"),
    (mutate(["tools"], []), "at least one tool"),
    (mutate(["tools"], [{"diameter": 6, "id": 1}, {"diameter": 8, "id": 1}]), "used twice"),
    (mutate(["allowance", "radial"], -1), "allowance.radial"),
    (mutate(["allowance", "radial"], 70), "no tool fits"),
    (mutate(["safe_z"], -30), "safe_z"),
    (mutate(["floor"], {"z": 5}), "below top_z"),
    (mutate(["floor"], KeyError), "floor: required"),
    (mutate(["strategy"], "zigzag"), "strategy"),
    (mutate(["boundary", 1, 0], "x"), "boundary[1][0]"),
    (mutate(["tools", 0, "diameterr"], 3), "unknown key"),
    (json.dumps(mutate(["top_z"], 0)).replace('"top_z": 0', '"top_z": 1e999'), "number overflow"),
]


@pytest.mark.parametrize("data,message", BAD, ids=[m for _, m in BAD])
def test_bad_input_gives_one_clear_line(cli, tmp_path, data, message):
    res = run(cli, data, tmp_path)
    assert res.returncode == 2
    lines = res.stderr.strip().splitlines()
    assert len(lines) == 1, res.stderr
    assert message in lines[0]
    assert res.stdout == ""


def test_missing_file_and_bad_usage(cli, tmp_path):
    res = subprocess.run([cli, "plan", str(tmp_path / "nope.json")], capture_output=True, text=True)
    assert res.returncode == 2 and len(res.stderr.strip().splitlines()) == 1 and "cannot read" in res.stderr
    res = subprocess.run([cli], capture_output=True, text=True)
    assert res.returncode != 0 and len(res.stderr.strip().splitlines()) == 1
    res = subprocess.run([cli, "plan", "a.json", "--frobnicate"], capture_output=True, text=True)
    assert res.returncode != 0 and len(res.stderr.strip().splitlines()) == 1


def hostile(name, change):
    data = load_shape(name)
    change(data)
    return data


def _add_tool(diameter):
    return lambda d: d["tools"].append({"diameter": diameter, "id": 9})


def _wild_vertex(d):
    d["boundary"][1] = [1e9, d["boundary"][1][1]]


# The inputs that ran past 30 s (up to 3.9 GB) in a fuzzing run, and their like:
# each now answers at once with one line naming the likely cause.
@pytest.mark.parametrize("change,message", [
    (_add_tool(1e-300), "is the diameter in mm?"),
    (_add_tool(0.001), "is the diameter in mm?"),
    (_add_tool(0.01), "is the diameter in mm?"),
    (_add_tool(1e9), "larger than any milling tool"),
    (_wild_vertex, "any machine travels: is it in mm?"),
    (lambda d: d.update(top_z=-1e12, safe_z=1e12), "top_z"),
    (lambda d: d.update(max_plunges=100), "more than max_plunges (100)"),
])
def test_absurd_scales_are_refused(cli, tmp_path, change, message):
    res = run(cli, hostile("benchmark", change), tmp_path, "-o", str(tmp_path / "p.json"))
    assert res.returncode == 2, res.stderr
    lines = res.stderr.splitlines()
    assert len(lines) == 1 and message in lines[0], lines
    assert not (tmp_path / "p.json").exists()


def test_tool_too_large_is_left_out(cli, tmp_path):
    out = tmp_path / "p.json"
    res = run(cli, hostile("convex", _add_tool(400)), tmp_path, "-o", str(out))
    assert res.returncode == 0, res.stderr
    plan = json.loads(out.read_text())
    assert any("T9 (400 mm)" in w for w in plan["warnings"]), plan.get("warnings")
    assert all(p["tool_id"] != 9 for p in plan["plunges"])
    assert_no_gouge(load_shape("convex"), plan)
