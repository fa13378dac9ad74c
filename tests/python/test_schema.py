"""docs/plan-input.schema.json and docs/plan-output.schema.json against the
command-line tool: the bundled inputs are valid and plan; what the tool writes
is valid output; the schema and the tool reject the same malformed inputs and
accept every documented field; docs/plan-format.md documents every field."""
import copy
import glob
import json
import os
import re
import subprocess

import jsonschema
import pytest

from conftest import SHAPES

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
DOCS = os.path.join(ROOT, "docs")
INPUTS = sorted(glob.glob(os.path.join(ROOT, "resources", "examples", "*.json")) +
                [os.path.join(SHAPES, n + ".json") for n in ("convex", "concave", "islands", "freeform", "neck")])


def schema(name):
    with open(os.path.join(DOCS, name)) as f:
        s = json.load(f)
    jsonschema.Draft202012Validator.check_schema(s)
    return jsonschema.Draft202012Validator(s)


@pytest.fixture(scope="module")
def input_schema():
    return schema("plan-input.schema.json")


@pytest.fixture(scope="module")
def output_schema():
    return schema("plan-output.schema.json")


def small():
    """A quick input: a 60 x 40 pocket, two plungers."""
    return {"version": 1, "boundary": [[0, 0], [60, 0], [60, 40], [0, 40]],
            "tools": [{"diameter": 16, "id": 1}, {"diameter": 6, "id": 2}], "top_z": 0, "safe_z": 5,
            "floor": {"z": -10}}


def plan(cli, data, tmp_path):
    src, out = tmp_path / "in.json", tmp_path / "plan.json"
    src.write_text(json.dumps(data))
    run = subprocess.run([cli, "plan", str(src), "-o", str(out)], capture_output=True, text=True, timeout=120)
    return run, (json.loads(out.read_text()) if run.returncode == 0 else None)


def errors(validator, data):
    return [e.message for e in validator.iter_errors(data)]


def assert_valid_plan(cli, input_schema, output_schema, tmp_path, data):
    """A valid input that plans to a valid output; returns the output."""
    assert not errors(input_schema, data)
    run, out = plan(cli, data, tmp_path)
    assert run.returncode == 0, run.stderr
    assert not errors(output_schema, out)
    return out


@pytest.mark.parametrize("path", INPUTS, ids=os.path.basename)
def test_bundled_inputs_are_valid_and_plan_to_valid_output(cli, input_schema, output_schema, tmp_path, path):
    with open(path) as f:
        assert_valid_plan(cli, input_schema, output_schema, tmp_path, json.load(f))


@pytest.mark.parametrize("extra", [
    {"tools": "auto", "tool_library": [{"diameter": 16}, {"diameter": 10}, {"diameter": 6}]},
    {"strategy": "grid", "grid": {"pattern": "square", "step": 0.6}},
    {"floor": {"expression": "-10 + 0.02*x"}, "allowance": {"radial": 0.2, "floor": 0.1}, "final_depth": -9.5},
    {"islands": [[[25, 15], [35, 15], [30, 25]]], "start": [60, 40], "sequencing": "annealing", "seed": 3},
], ids=["auto", "grid", "expression", "islands"])
def test_optional_features_are_valid_and_plan_to_valid_output(cli, input_schema, output_schema, tmp_path, extra):
    data = dict(small(), **extra)
    if extra.get("tools") == "auto":
        data["tools"] = "auto"
    out = assert_valid_plan(cli, input_schema, output_schema, tmp_path, data)
    if "tool_library" in extra:
        assert out["tool_selection"]["chosen"]


def test_every_documented_field_is_read_by_the_tool(cli, input_schema, tmp_path):
    """Each optional field at its documented default is valid and accepted; an
    unknown one is refused by both (so the schema lists exactly what the tool reads)."""
    props = input_schema.schema["properties"]
    tried = 0
    for key, spec in props.items():
        defaults = {k: v["default"] for k, v in spec.get("properties", {}).items() if "default" in v}
        value = spec.get("default", defaults or None)
        if key in small() or value is None:
            continue
        data = dict(small(), **{key: value})
        assert not errors(input_schema, data), key
        run, _ = plan(cli, data, tmp_path)
        assert run.returncode == 0, (key, run.stderr)
        tried += 1
    assert tried >= 10
    data = dict(small(), allowances={"radial": 1})
    assert errors(input_schema, data)
    run, _ = plan(cli, data, tmp_path)
    assert run.returncode == 2 and "allowances" in run.stderr


def mutations():
    """Malformed inputs, each with what breaks it."""
    cases = []

    def case(name, change):
        data = copy.deepcopy(small())
        change(data)
        cases.append(pytest.param(data, id=name))

    case("no boundary", lambda d: d.pop("boundary"))
    case("no floor", lambda d: d.pop("floor"))
    case("no tools", lambda d: d.pop("tools"))
    case("two floors", lambda d: d["floor"].update(expression="x"))
    case("floor key", lambda d: d["floor"].update(height=1) or d["floor"].pop("z"))
    case("point of three", lambda d: d["boundary"][0].append(1))
    case("string coordinate", lambda d: d["boundary"][1].__setitem__(0, "60"))
    case("tool without diameter", lambda d: d["tools"][0].pop("diameter"))
    case("tool key", lambda d: d["tools"][0].update(radius=8))
    case("tool shape", lambda d: d["tools"][0].update(shape="conical"))
    case("tool id zero", lambda d: d["tools"][0].update(id=0))
    case("negative diameter", lambda d: d["tools"][1].update(diameter=-6))
    case("version 2", lambda d: d.update(version=2))
    case("negative seed", lambda d: d.update(seed=-1))
    case("strategy", lambda d: d.update(strategy="spiral"))
    case("packing order", lambda d: d.update(packing_order="random"))
    case("growth pattern", lambda d: d.update(growth_pattern="spiral"))
    case("sequencing", lambda d: d.update(sequencing="greedy"))
    case("min coverage", lambda d: d.update(min_coverage=1.5))
    case("contact ratio", lambda d: d.update(contact_ratio=0.2))
    case("negative allowance", lambda d: d.update(allowance={"radial": -1}))
    case("grid pattern", lambda d: d.update(strategy="grid", grid={"pattern": "hex"}))
    case("grid step", lambda d: d.update(strategy="grid", grid={"step": 2}))
    case("rise factor", lambda d: d.update(selection={"rise_factor": 1.0}))
    case("time model key", lambda d: d.update(time_model={"speed": 1}))
    case("auto without library", lambda d: d.update(tools="auto"))
    case("library without auto", lambda d: d.update(tool_library=[{"diameter": 6}]))
    return cases


@pytest.mark.parametrize("data", mutations())
def test_schema_and_tool_refuse_the_same_malformed_input(cli, input_schema, tmp_path, data):
    assert errors(input_schema, data)
    run, _ = plan(cli, data, tmp_path)
    assert run.returncode == 2
    assert len(run.stderr.strip().splitlines()) == 1


def test_plan_format_documents_every_field(input_schema, output_schema):
    with open(os.path.join(DOCS, "plan-format.md")) as f:
        text = f.read()
    documented = set(re.findall(r"^\| `([a-z_.\[\]]+)`", text, re.M))

    def fields(spec, prefix):
        for key, sub in spec.get("properties", {}).items():
            name = prefix + key
            yield name
            if sub.get("type") == "object":
                yield from fields(sub, name + ".")
            if sub.get("type") == "array" and isinstance(sub.get("items"), dict):
                yield from fields(sub["items"], name + "[].")

    tool = input_schema.schema["$defs"]["tool"]
    wanted = set(fields(input_schema.schema, "")) | set(fields(tool, "tools[]."))
    wanted |= {"output." + n for n in fields(output_schema.schema, "")}
    missing = sorted(wanted - documented)
    assert not missing, missing
