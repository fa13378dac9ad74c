"""Every default docs/plan-format.md gives for an input field is the planner's:
each is planned both ways, written out and left out, and the plans compared.
A default the page states wrongly fails here (a field whose default is a
formula or "unlimited" is said in words, and is left to its own tests)."""
import copy
import json
import os
import re

import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def documented_defaults():
    """(field, value) for every row of the input table whose default is a
    number, a boolean, a quoted string or {}."""
    text = open(os.path.join(ROOT, "docs", "plan-format.md")).read()
    table = text.split("## Input", 1)[1].split("\n## ", 1)[0]
    out = []
    for field, default in re.findall(r"^\| `([a-z_.\[\]]+)` \| [^|]* \| ([^|]+) \|", table, re.M):
        default = default.strip()
        if re.fullmatch(r"-?\d+(\.\d+)?", default):
            value = float(default) if "." in default else int(default)
        elif default in ("true", "false"):
            value = default == "true"
        elif re.fullmatch(r'`"[a-z_]+"`', default):
            value = default.strip('`"')
        elif default == "`{}`":
            value = {}
        else:
            continue
        out.append((field, value))
    return out


DEFAULTS = documented_defaults()

# Fields that act only with another one: written out with it on both sides.
NEEDS = {
    "grid.": {"strategy": "grid"},
    "selection.": {"tools": "auto"},
    "tools[].growth": {},
}


def base():
    """A job every field means something in: a sculptured floor (floor stock,
    lead-outs over steps), an island, pecks, two plungers from a library."""
    return {"boundary": [[0, 0], [70, 0], [70, 45], [0, 45]], "islands": [[[30, 15], [42, 15], [36, 27]]],
            "tools": [{"diameter": 12}, {"diameter": 6}],
            "top_z": 0, "floor": {"expression": "-30 + 2 * sin(x / 8)"}}


def written(data, field, value):
    """data with the field set to value (dotted paths; tools[] on every tool)."""
    data = copy.deepcopy(data)
    if field.startswith("tools[]."):
        key = field.split(".", 1)[1]
        targets = data["tool_library"] if data.get("tools") == "auto" else data["tools"]
        for t in targets:
            t[key] = value
        return data
    *path, key = field.split(".")
    at = data
    for p in path:
        at = at.setdefault(p, {})
    at[key] = value
    return data


def with_needs(data, field):
    for prefix, extra in NEEDS.items():
        if field.startswith(prefix):
            for k, v in extra.items():
                if k == "tools" and v == "auto":
                    data["tool_library"] = data.pop("tools")
                data[k] = v
    return data


def comparable(plan):
    plan = dict(plan)
    plan["stats"] = {k: v for k, v in plan["stats"].items() if k != "planning_seconds"}
    plan.pop("summary", None)
    return json.dumps(plan, sort_keys=True)


def test_the_page_gives_defaults_to_test():
    fields = [f for f, _ in DEFAULTS]
    assert len(fields) >= 25, fields
    for must in ("safe_z", "max_wall_stock", "min_coverage", "contact_ratio", "lead_out", "tools[].feed",
                 "time_model.rapid_rate", "allowance.radial", "rapid_clearance", "holder_clearance"):
        assert must in fields, must


@pytest.mark.parametrize("field, value", DEFAULTS, ids=[f for f, _ in DEFAULTS])
def test_each_documented_default_is_the_planners(plunge, field, value):
    left_out = with_needs(base(), field)
    plans = [plunge.plan(left_out), plunge.plan(written(left_out, field, value))]
    assert comparable(plans[0]) == comparable(plans[1]), "%s: the page says %r" % (field, value)


def test_a_wrong_default_would_be_caught(plunge):
    """The comparison tells a changed value apart: the page's own defaults
    shifted plan differently (what a stale page would claim)."""
    for field, shifted in (("max_wall_stock", 1.5), ("lead_out", 0.8), ("safe_z", 9), ("contact_ratio", 0.9)):
        left_out = base()
        assert comparable(plunge.plan(left_out)) != comparable(plunge.plan(written(left_out, field, shifted))), field
