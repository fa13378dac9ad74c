"""freecad_plugin/plan_input.py, headless on plain data (no FreeCAD here): the
operation's settings become a plan input the schema accepts and the planner
plans, each setting where the plan format puts it; bad settings are refused
before any geometry."""
import json
import os
import subprocess
import sys

import jsonschema
import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, ROOT)

from freecad_plugin import plan_input  # noqa: E402

BOX = [[0, 0], [120, 0], [120, 80], [0, 80]]
ISLAND = [[50, 30], [70, 30], [60, 50]]
TOOLS = [{"diameter": 20, "id": 2, "feed": 300}, {"diameter": 8, "id": 3, "feed": 200}]
TIME = {"rapid_rate": 5000, "retract_rate": 5000, "tool_change_seconds": 20}


def settings(**changes):
    heights = dict(start_depth=0.0, final_depth=-20.0, safe_height=5.0, clearance_height=10.0)
    heights.update(changes)
    return plan_input.Settings(**heights)


def made(s, **pocket):
    return plan_input.plan_input(s, TOOLS, TIME, BOX, [ISLAND], pocket.pop("floor", {"z": -20.0}), **pocket)


@pytest.fixture(scope="module")
def schema():
    with open(os.path.join(ROOT, "docs", "plan-input.schema.json")) as f:
        return jsonschema.Draft202012Validator(json.load(f))


def test_plan_input_imports_no_freecad():
    """In an interpreter of its own: what this one imported does not count."""
    code = ("import sys; sys.path.insert(0, %r); from freecad_plugin import plan_input; "
            "print(sorted(m for m in ('FreeCAD', 'Path', 'Part', 'PySide') if m in sys.modules))" % ROOT)
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip() == "[]", out


def test_the_defaults_make_a_plan(schema, plunge):
    data = made(settings())
    schema.validate(data)
    assert data["tools"] == "auto" and data["tool_library"] == TOOLS  # the tool choice is on by default
    assert data["allowance"]["floor"] == 0.0 and data["allowance"]["radial"] == pytest.approx(0.0, abs=1e-5)
    assert data["lead_out"] == 0.5 and data["stock_aware_heights"] and data["peck"]
    plan = plunge.plan(data)
    assert plan["plunges"] and all(p["z"] >= -20.0 - 1e-9 for p in plan["plunges"])


@pytest.mark.parametrize("change, key, value", [
    ({"canned_cycle": True}, "lead_out", 0.0),
    ({"canned_cycle": True}, "stock_aware_heights", False),
    ({"min_coverage": 98.0}, "min_coverage", 0.98),
    ({"max_wall_stock": 0.4}, "max_wall_stock", 0.4),
    ({"max_floor_stock": 0.0}, "max_floor_stock", 0.0),
    ({"growth_pattern": "Rows"}, "growth_pattern", "rows"),
    ({"strategy": "Grid (square)"}, "grid", {"pattern": "square"}),
    ({"strategy": "Grid (square)"}, "strategy", "grid"),
    ({"holder_clearance": 2.5}, "holder_clearance", 2.5),
    ({"dwell": 0.4}, "peck_dwell", 0.4),
])
def test_each_setting_goes_where_the_plan_format_puts_it(schema, plunge, change, key, value):
    data = made(settings(auto_select=False, **change))
    schema.validate(data)
    assert data[key] == value
    assert plunge.plan(data)["plunges"]


def test_tools_peck_depth_deviation_sections_and_material(schema, plunge):
    material = {"origin": [-10, -10], "spacing": 2.0, "nx": 70, "ny": 50, "top": [-5.0] * 3500}
    sections = [{"z": -10.0, "boundary": BOX, "islands": []}]
    data = made(settings(auto_select=False, peck_depth=12.0, radial_allowance=0.5), deviation=0.02,
                sections=sections, material=material)
    schema.validate(data)
    assert [t["peck_depth"] for t in data["tools"]] == [12.0, 12.0]
    assert "peck_depth" not in TOOLS[0]  # the caller's tools are not changed
    assert data["allowance"]["radial"] == pytest.approx(0.52, abs=1e-5)
    assert data["sections"] == sections and data["material"] is material
    plan = plunge.plan(data)
    # From the material at -5: every plunge rapids down to just above it.
    assert plan["stats"]["rest_material"]
    assert max(p["approach_z"] for p in plan["plunges"]) <= -5.0 + 1.0 + 1e-9


@pytest.mark.parametrize("change, lengths, message", [
    ({}, [("TC: 20 mm", 15.0)], "TC: 20 mm is 15 mm long, shorter than the pocket is deep (20 mm)"),
    ({"safe_height": 12.0}, [], "the safe height is above the clearance height"),
    ({"final_depth": 0.0}, [], "the start depth must be above the final depth"),
])
def test_bad_settings_are_refused_by_name(change, lengths, message):
    with pytest.raises(ValueError, match=message.replace("(", r"\(").replace(")", r"\)")):
        plan_input.check(settings(**change), lengths)
    plan_input.check(settings(), [("TC: 20 mm", 40.0), ("TC: 8 mm", 0.0)])  # 0: length not known


def test_each_default_is_the_operations():
    """The Settings' defaults are the properties' defaults (PlungeRough takes
    them from DEFAULTS): what the handbook promises of a new operation."""
    d = plan_input.DEFAULTS
    assert d["radial_allowance"] == 0.0 and d["floor_allowance"] == 0.0
    assert d["max_wall_stock"] == 1.0 and d["max_floor_stock"] == 1.0 and d["lead_out"] == 0.5
    assert d["auto_select"] and d["stock_aware_heights"] and d["peck"] and not d["canned_cycle"]
    addon = open(os.path.join(ROOT, "freecad_plugin", "PlungeRough.py")).read()
    for name in ("radial_allowance", "floor_allowance", "max_wall_stock", "max_floor_stock", "lead_out",
                 "min_coverage", "auto_select", "tool_change_time", "holder_clearance"):
        assert 'DEFAULTS["%s"]' % name in addon, name
