"""Posting a job with Plunge Rough: the G-code parsed back must be the plan."""
import json

import pytest

import parts
from conftest import build_op
from freecad_plugin import PlungeRough
from gcode import parse_gcode, replay
from machine_check import assert_machinable, check_program
from freecad_plugin.compat import post_job


def plan_plunges(op):
    return [(p["tool_id"], p["x"], p["y"], p["z"]) for p in PlungeRough.plan_of(op)["plunges"]]


def assert_matches(posted, expected):
    assert len(posted) == len(expected)
    for (t1, x1, y1, z1), (t2, x2, y2, z2) in zip(posted, expected):
        assert t1 == t2 and abs(x1 - x2) < 2e-3 and abs(y1 - y2) < 2e-3 and abs(z1 - z2) < 2e-3


@pytest.mark.bundle
@pytest.mark.parametrize("canned", [False, True])
def test_linuxcnc(doc, tmp_path, canned):
    job, op, tcs = build_op(doc, parts.islands_part(), sculptured=False, canned=canned, peck=3.0 if canned else 0.0)
    text = post_job(job, "linuxcnc", "--no-header --no-show-editor")
    blocks = parse_gcode(text)
    plunges, low = replay(blocks, op.SafeHeight.Value)
    if canned:
        assert not low, "a canned cycle's rapid crosses below the safe height"
    else:  # stock-aware heights: the posted program against a simulated stock
        data = json.loads(op.PlanData)["input"]
        assert_machinable(check_program(data, data["tools"], text))
    assert_matches(plunges, plan_plunges(op))
    # A tool change before each tool's plunges, largest first.
    changes = [int(w["T"]) for codes, w in blocks if "M6" in codes and "T" in w]
    assert changes == [int(tc.ToolNumber) for tc in tcs]
    if canned:
        assert "G83" in text and "G80" in text and ("G98" in text or "G99" in text)


def test_grbl_translates_cycles(doc, tmp_path):
    job, op, tcs = build_op(doc, parts.islands_part(), sculptured=False, canned=True)
    text = post_job(job, "grbl", "--no-header --no-show-editor --translate_drill --tool-change")
    blocks = parse_gcode(text)  # comments removed: grbl_post keeps the cycle as one
    assert not any(c in ("G81", "G83") for codes, _ in blocks for c in codes)  # Grbl cannot run them
    plunges, low = replay(blocks, op.SafeHeight.Value)
    assert not low
    assert_matches(plunges, plan_plunges(op))
