"""The plan's estimated time against the program it posts, timed by an
independent reader of the G-code (machine_check.parse, not the planner's time
model): rapids across at the time model's rapid rate and up or down at its
retract rate, feeds along their 3D length at their F words, dwells, 20 s per
M6. With engagement limits, flute-length levels, pecks, lead-outs and
stock-aware heights on, the estimate is within 5 % of the program's time
(what the automatic tool choice compares sets by)."""
import json
import math
import os
import subprocess

import pytest

from conftest import limited, load_shape

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from machine_check import parse

RAPID, RETRACT, CHANGE = 10000.0, 5000.0, 20.0  # the time model's defaults (docs/plan-format.md)


def program_minutes(gcode):
    """Minutes of a posted program under the time model's rates."""
    x = y = z = 0.0
    feed, motion, total = None, None, 0.0
    for codes, w in parse(gcode):
        if "M6" in codes:
            total += CHANGE / 60.0
        if "G4" in codes:
            total += w.get("P", 0.0) / 60.0
            continue
        for c in codes:
            if c in ("G0", "G1"):
                motion = c
        assert not any(c in ("G81", "G82", "G83") for c in codes), "explicit moves expected"
        feed = w.get("F", feed)
        if not any(k in w for k in "XYZ"):
            continue
        nx, ny, nz = w.get("X", x), w.get("Y", y), w.get("Z", z)
        if motion == "G0":
            total += math.hypot(nx - x, ny - y) / RAPID + abs(nz - z) / RETRACT
        elif motion == "G1":
            total += math.dist((x, y, z), (nx, ny, nz)) / feed
        x, y, z = nx, ny, nz
    return total


def deep(data):
    """The pocket 40 mm deep, plungers with 15 mm flutes pecking every 6 mm."""
    data = json.loads(json.dumps(data))
    data["top_z"], data["floor"] = 0.0, {"z": -40.0}
    for t in data["tools"]:
        t["flute_length"], t["peck_depth"] = 15.0, 6.0
    return data


CASES = {
    "islands": lambda: load_shape("islands"),
    "islands 0.25 D": lambda: limited(load_shape("islands"), 0.25),
    "neck deep, levels and pecks": lambda: deep(load_shape("neck")),
    "freeform deep 0.5 D": lambda: limited(deep(load_shape("freeform")), 0.5),
    "example sculptured 0.5 D": lambda: limited(json.load(open(os.path.join(ROOT, "resources", "examples",
                                                                             "sculptured.json"))), 0.5),
}


def post(cli, data, tmp_path):
    src, out, nc = tmp_path / "in.json", tmp_path / "plan.json", tmp_path / "plan.nc"
    src.write_text(json.dumps(data))
    run = subprocess.run([cli, "plan", str(src), "-o", str(out), "--gcode", str(nc)], capture_output=True, text=True,
                         timeout=600)
    assert run.returncode == 0, run.stderr
    return json.loads(out.read_text()), nc.read_text()


@pytest.mark.parametrize("case", list(CASES))
def test_estimate_is_the_posted_programs_time(cli, tmp_path, case):
    data = CASES[case]()
    data.setdefault("peck_dwell", 0.5)
    plan, gcode = post(cli, data, tmp_path)
    s = plan["stats"]
    if "neck" in case:
        assert s["pecked_plunges"] > 0 and s["levels"] > 1  # the case has what it is for
    assert s["stock_aware_heights"] if "stock_aware_heights" in s else True
    program = program_minutes(gcode)
    assert s["estimated_minutes"] == pytest.approx(program, rel=0.05), (s["estimated_minutes"], program)
