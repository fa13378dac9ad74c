"""The pybind11 module under Debian's python3, the interpreter FreeCAD embeds."""
import re
import math
import sys

import pytest

from conftest import load_shape
from geometry_check import assert_no_gouge, core_left, coverage



def test_runs_under_debians_python(plunge):
    """The module is built for Debian's python3, the interpreter FreeCAD embeds
    (3.11 on Debian 12, 3.13 on Debian 13): same version as FreeCAD's own Python,
    and an extension suffix this interpreter loads."""
    import shutil
    import subprocess
    import sysconfig
    assert sys.executable.startswith("/usr/bin/python3")
    assert plunge.__file__.endswith(sysconfig.get_config_var("EXT_SUFFIX"))
    if shutil.which("freecadcmd"):
        run = subprocess.run(["freecadcmd", "-c", "import sys; print('PY=%d.%d' % sys.version_info[:2]); "
                              "sys.stdout.flush()"], capture_output=True, text=True, timeout=120, cwd="/tmp")
        found = [l for l in run.stdout.replace("\r", "\n").splitlines() if l.startswith("PY=")]
        assert found, run.stdout[-500:] + run.stderr[-500:]
        assert found[0] == "PY=%d.%d" % sys.version_info[:2]


def test_plan_contract(plunge):
    data = load_shape("concave")
    plan = plunge.plan(data)
    assert set(plan) >= {"plunges", "stats"}
    assert set(plan["stats"]) >= {"plunge_count", "per_tool", "region_area", "accessible_area", "covered_area",
                                  "coverage", "travel_length", "planning_seconds"}
    for p in plan["plunges"]:
        assert {"x", "y", "diameter", "tool_id", "z", "approach_z", "retract_z", "engagement", "level", "start",
                "start_hole"} <= set(p) <= {"x", "y", "diameter", "tool_id", "z", "approach_z", "retract_z",
                                            "engagement", "level", "start", "start_hole", "lead_out",
                                            "lead_out_z", "pecks"}
    assert_no_gouge(data, plan)
    assert max(core_left(data, plan, 1.0), default=0.0) < 0.01  # the default wall band
    assert plunge.plan(data)["plunges"] == plan["plunges"]  # deterministic
    # Without a band: covered down to min_coverage, as before the band existed.
    assert coverage(data, plunge.plan(dict(data, max_wall_stock=0))) >= 0.995


def test_tuples_and_defaults(plunge):
    plan = plunge.plan({"boundary": ((0, 0), (80, 0), (80, 50), (0, 50)), "tools": [{"diameter": 10}],
                        "floor": {"z": -5}})
    assert plan["plunges"] and all(p["tool_id"] == 1 for p in plan["plunges"])
    assert all(p["z"] == -5 for p in plan["plunges"])


@pytest.mark.parametrize("change,message", [
    ({"boundary": [[0, 0], [1, 0]]}, "at least 3 distinct points"),
    ({"tools": [{"diameter": float("nan")}]}, "not a finite number"),
    ({"tools": [{"diameter": float("inf")}]}, "not a finite number"),
    ({"boundary": [[0, 0], [100, 0], [100, float("nan")], [0, 50]]}, "finite"),
    ({"tools": "big"}, "tools"),
    ({"floor": {"z": "low"}}, "floor.z"),
    ({"floor": {"z": -5}, "strategy": 3}, "strategy"),
    ({"growth_pattern": "spiral"}, "growth_pattern: unknown pattern 'spiral'"),
    ({"extra": object()}, "unsupported value"),
    ({"islands": [[[300, 300], [310, 300], [305, 310]]]}, "outside the boundary"),
    ({"tools": [{"diameter": 0.001, "id": 1}]}, "is the diameter in mm?"),
    ({"tools": [{"diameter": 12, "id": 1}], "max_plunges": 10}, "more than max_plunges (10)"),
    ({"allowance": {"radial": 1e308}}, "allowance.radial 1.000e+308 mm is beyond"),
])
def test_bad_input_raises_value_error(plunge, change, message):
    data = load_shape("islands")
    data.update(change)
    with pytest.raises(ValueError, match=re.escape(message)):
        plunge.plan(data)


def test_errors_by_kind(plunge):
    """Bad input is a ValueError; a fault of the planner (plunge::InternalError)
    a RuntimeError, never taken for the user's mistake."""
    assert issubclass(plunge.PlanError, ValueError) and not issubclass(plunge.PlanError, RuntimeError)
    assert issubclass(plunge.InternalError, RuntimeError) and not issubclass(plunge.InternalError, ValueError)


def test_summary_and_start_hole_tools(plunge):
    data = load_shape("islands")
    plan = plunge.plan(data)
    s = plan["stats"]
    summary = plan["summary"]
    assert summary.startswith("%d plunges (" % s["plunge_count"]) and "coverage %.2f %%" % (100 * s["coverage"]) in summary
    assert "walls up to %.2f mm" % s["max_wall_stock_left"] in summary and "about %.1f min" % s["estimated_minutes"] in summary
    tools = [{"id": 1, "diameter": 20, "center_cutting": False, "core_diameter": 8},
             {"id": 2, "diameter": 10}, {"id": 3, "diameter": 6}, {"id": 4, "diameter": 12}]
    assert plunge.start_hole_tools(tools) == {1: 2}  # the smallest centre-cutting tool as wide as the core
    with pytest.raises(ValueError, match="centre-cutting tool at least 8"):
        plunge.start_hole_tools(tools[:1] + tools[2:3])
    for bad in ({"id": 1, "diameter": 20}, "tools", 3):  # not a list: named, as in plan()
        with pytest.raises(ValueError, match="tools: expected a list"):
            plunge.start_hole_tools(bad)


def test_non_string_keys(plunge):
    with pytest.raises(ValueError, match="keys must be strings"):
        plunge.plan({1: 2})


def test_tour(plunge):
    pts = [(math.cos(k), math.sin(k)) for k in range(30)]
    order = plunge.tour(pts)
    assert sorted(order) == list(range(30))
    # An open path from a place is short with the way there: on a line, from
    # 5.4, out to the nearer end and back (12.6), not first to the nearest point.
    line = [(float(x), 0.0) for x in (3, 7, 0, 9, 5, 1, 8, 2, 6, 4)]
    path = plunge.tour(line, closed=False, start=(5.4, 0))
    assert sorted(path) == list(range(10))
    way = [(5.4, 0.0)] + [line[i] for i in path]
    assert sum(math.dist(way[i], way[i + 1]) for i in range(10)) == pytest.approx(12.6)
    assert plunge.tour([]) == []
    with pytest.raises(ValueError, match="finite"):
        plunge.tour([(0, 0), (float("nan"), 1)])
    with pytest.raises(ValueError, match="unknown method"):
        plunge.tour(pts, method="genetic")


def test_tour_methods_and_seed(plunge):
    import random
    rng = random.Random(5)
    pts = [(rng.uniform(0, 50), rng.uniform(0, 50)) for _ in range(300)]

    def length(order):
        return sum(math.dist(pts[order[i - 1]], pts[order[i]]) for i in range(len(order)))

    local = plunge.tour(pts, method="local_search", seed=3)
    annealed = plunge.tour(pts, method="annealing", seed=3)
    assert sorted(local) == sorted(annealed) == list(range(300))
    assert plunge.tour(pts, method="annealing", seed=3) == annealed
    # Both far below a random order (about 0.52 * n * side for uniform points).
    assert length(local) < 0.2 * length(list(range(300)))
    assert length(annealed) < 0.25 * length(list(range(300)))


def test_plan_sequencing_option(plunge):
    data = load_shape("convex")
    data["sequencing"] = "annealing"
    annealed = plunge.plan(data)
    default = plunge.plan(load_shape("convex"))
    assert len(annealed["plunges"]) == len(default["plunges"])
    assert annealed["stats"]["travel_length"] > 0
    data["sequencing"] = "ants"
    with pytest.raises(ValueError, match="sequencing"):
        plunge.plan(data)


def test_progress_is_reported_and_the_plan_unchanged(plunge):
    seen = []
    data = load_shape("islands")
    plan = plunge.plan(data, progress=lambda f, stage: seen.append((f, stage)))
    assert len(seen) >= 3 and seen[0] == (0.0, "checking the pocket")
    assert all(a[0] <= b[0] for a, b in zip(seen, seen[1:])) and seen[-1][0] <= 1.0
    assert plan["plunges"] == plunge.plan(data)["plunges"]


def test_progress_cancels(plunge):
    calls = []

    def stop(fraction, stage):
        calls.append(fraction)
        return False

    # A cancel is not bad input: plunge.Cancelled, which no ValueError handler takes.
    with pytest.raises(plunge.Cancelled, match="planning cancelled") as cancelled:
        plunge.plan(load_shape("islands"), progress=stop)
    assert not isinstance(cancelled.value, ValueError)
    assert len(calls) == 1
    with pytest.raises(ValueError, match="progress: expected a callable"):
        plunge.plan(load_shape("islands"), progress=3)


def test_progress_exception_goes_through(plunge):
    class Stop(Exception):
        pass

    def boom(fraction, stage):
        raise Stop()

    with pytest.raises(Stop):
        plunge.plan(load_shape("islands"), progress=boom)


def test_ctrl_c_interrupts_a_long_plan(plunge):
    """Ctrl+C (here simulated: the interpreter's SIGINT flag) stops planning with
    KeyboardInterrupt, the GIL being released meanwhile."""
    import _thread
    import threading
    timer = threading.Timer(0.2, _thread.interrupt_main)
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            plunge.plan(load_shape("benchmark"))
            plunge.plan(load_shape("benchmark"))  # in case the first ended before the timer
    finally:
        timer.cancel()
