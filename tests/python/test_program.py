"""The planner as a program (plunge-rough call, docs/cli.md): the same answer
as the module for the same request, apart from timings; progress on stderr,
one line per tick; one clear line for a bad request; a kill stops it."""
import json
import math
import re
import subprocess
import time

import pytest

from conftest import load_shape

PROGRESS = re.compile(r"^progress (\d\.\d{4}) (.+)$")


def call(cli, request, timeout=300):
    return subprocess.run([cli, "call"], input=json.dumps(request), capture_output=True, text=True, timeout=timeout)


def without_timings(answer):
    answer = json.loads(json.dumps(answer))
    answer["stats"].pop("planning_seconds")
    return answer


def bowl(x, y):
    return -25 + 3 * math.sin(x / 17.0) * math.cos(y / 23.0) + 0.01 * x


def bowl_mesh(lo, hi, step):
    """The bowl on a grid, two triangles a cell, and its distance from the grid."""
    nx, ny = int((hi[0] - lo[0]) / step), int((hi[1] - lo[1]) / step)
    vertices = [[lo[0] + i * step, lo[1] + j * step, bowl(lo[0] + i * step, lo[1] + j * step)]
                for j in range(ny + 1) for i in range(nx + 1)]
    at = lambda i, j: j * (nx + 1) + i  # noqa: E731
    triangles = []
    for j in range(ny):
        for i in range(nx):
            triangles += [[at(i, j), at(i + 1, j), at(i + 1, j + 1)], [at(i, j), at(i + 1, j + 1), at(i, j + 1)]]
    # Second derivatives under 3 / 17^2: a chord of `step` is off by less than that / 8 * step^2 * 2.
    return {"vertices": vertices, "triangles": triangles, "deviation": 3 / 17.0 ** 2 / 4 * step * step}


def golden(name):
    """The golden inputs: every test shape, and the freeform shape over an
    expression floor and over its mesh with flat and ball plungers."""
    if name in ("expression", "mesh"):
        data = load_shape("freeform")
        data["tools"] = [{"id": 1, "diameter": 20}, {"id": 2, "diameter": 10, "shape": "ball"}]
        if name == "expression":
            data["floor"] = {"expression": "-25 + 3*sin(x/17)*cos(y/23) + 0.01*x"}
        else:
            xs = [p[0] for p in data["boundary"]]
            ys = [p[1] for p in data["boundary"]]
            data["floor"] = {"mesh": bowl_mesh((min(xs) - 1, min(ys) - 1), (max(xs) + 1, max(ys) + 1), 1.0)}
        return data
    return load_shape(name)


GOLDEN = ["convex", "concave", "islands", "freeform", "neck", "benchmark", "expression", "mesh"]


@pytest.mark.parametrize("name", GOLDEN)
def test_module_and_program_give_the_same_plan(plunge, cli, name):
    data = golden(name)
    by_module = plunge.plan(data, svg=True)
    run = call(cli, {"call": "plan", "input": data, "svg": True})
    assert run.returncode == 0, run.stderr
    by_program = json.loads(run.stdout)
    assert by_program["plunges"] and by_program["svg"].startswith("<svg ")
    assert without_timings(by_program) == without_timings(by_module)
    # Progress: one line per tick, every line a fraction and a stage.
    lines = run.stderr.splitlines()
    assert lines and all(PROGRESS.match(line) for line in lines), lines[:5]
    assert lines[0] == "progress 0.0000 checking the pocket"


def test_start_hole_tools_and_sweep_as_the_module(plunge, cli):
    tools = [{"id": 1, "diameter": 20, "center_cutting": False, "core_diameter": 8},
             {"id": 2, "diameter": 10}, {"id": 3, "diameter": 6}]
    run = call(cli, {"call": "start_hole_tools", "tools": tools})
    assert run.returncode == 0 and json.loads(run.stdout) == {"1": 2} and plunge.start_hole_tools(tools) == {1: 2}
    material = {"origin": [0, 0], "spacing": 0.5, "nx": 80, "ny": 60, "top": [0.0] * 4800}
    tool = {"diameter": 8, "shape": "bull", "corner_radius": 1}
    moves = [[5, 5, 10, 5, 5, -4], [5, 5, -4, 35, 20, -6], [35, 20, -6, 35, 20, 10]]
    run = call(cli, {"call": "sweep", "material": material, "tool": tool, "moves": moves})
    assert run.returncode == 0, run.stderr
    top = json.loads(run.stdout)["top"]
    assert top == plunge.sweep(material, tool, moves) and min(top) < -5.9


def test_about_names_the_build(plunge, cli):
    run = call(cli, {"call": "about"})
    about = json.loads(run.stdout)
    assert about == plunge.about()
    assert about["system"] == "linux" and set(about["floors"]) == {"z", "expression", "mesh", "brep"}
    assert about["platform"] == "linux-x86_64"


@pytest.mark.parametrize("request_text,message", [
    ("[1, 2", "the request is not JSON"),
    ('{"call": "fly"}', 'call: unknown call "fly" (plan, start_hole_tools, sweep or about)'),
    ('{"call": "plan"}', 'plan: "input" is required'),
    ('{"call": "plan", "input": {"version": 1}}', "boundary"),
    ('{"call": "sweep", "material": {}, "tool": {"diameter": 5}, "moves": []}', "material."),
])
def test_a_bad_request_is_one_line_and_exit_2(cli, request_text, message):
    run = subprocess.run([cli, "call"], input=request_text, capture_output=True, text=True, timeout=60)
    assert run.returncode == 2 and run.stdout == ""
    errors = [line for line in run.stderr.splitlines() if not line.startswith("progress ")]
    assert len(errors) == 1 and errors[0].startswith("plunge-rough: error: ") and message in errors[0], errors


def killed_while_planning(argv, env=None):
    """The program (argv) killed once it reports planning a long plan: how
    long it took to end, and how it ended."""
    proc = subprocess.Popen(argv + ["call"], stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            env=env)
    data = load_shape("benchmark")
    data["tools"].append({"id": 9, "diameter": 3})  # long enough to be killed while planning
    proc.stdin.write(json.dumps({"call": "plan", "input": data}).encode())
    proc.stdin.close()
    assert proc.stderr.readline().startswith(b"progress ")
    start = time.monotonic()
    proc.kill()
    proc.wait(timeout=10)
    return time.monotonic() - start, proc.returncode


def test_a_kill_stops_it_at_once(cli):
    """The addon cancels by killing the program: it must not hold on."""
    took, code = killed_while_planning([cli])
    assert took < 1.0 and code == -9


def test_a_floor_no_plunger_can_follow_is_refused_first(plunge, cli):
    """The 600 x 400 mm plate over -25+sin(x*1e6), a floor that rises and falls
    every few micrometres: mutation fuzzing found it still planning after 15
    minutes. Refused before planning, with the reason (the subprocess's
    timeout only guards against the hang this was)."""
    data = load_shape("benchmark")
    data["floor"] = {"expression": "-25+sin(x*1e6)"}
    run = subprocess.run([cli, "call"], input=json.dumps({"call": "plan", "input": data}), capture_output=True,
                         text=True, timeout=120)
    errors = [line for line in run.stderr.splitlines() if not line.startswith("progress ")]
    assert run.returncode == 2 and run.stdout == "" and len(errors) == 1, errors
    assert "floor.expression: it rises and falls by" in errors[0] and "finer than any plunger" in errors[0]
    with pytest.raises(ValueError, match="finer than any plunger"):
        plunge.plan(data)


def test_the_depth_budget_warning_fits_the_floor(plunge):
    """Where the depth search runs out of budget the plan says so, naming the
    kind of floor and a remedy for that kind: an expression is not told to
    export its faces more cleanly."""
    data = load_shape("convex")
    data["floor"] = {"expression": "-25+0.001*sin(x*1e6)"}  # too fine for the search, too small to refuse
    plan = plunge.plan(data)
    said = [w for w in plan["warnings"] if w.startswith("the depth search ran out of its budget")]
    assert plan["stats"]["depth_fallbacks"] >= 1 and len(said) == 1, plan["warnings"]
    assert "of the floor expression" in said[0] and "a smoother expression avoids it" in said[0]
    assert "export" not in said[0] and "faces" not in said[0]
