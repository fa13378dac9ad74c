"""The library's layers (docs/architecture.md): every #include of cpp/ names a
file of its own layer or below, and every file is in the drawing."""
import os
import re

import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
CPP = os.path.join(ROOT, "cpp")


def layers():
    """{module: layer} from docs/architecture.md's drawing (the block after <!-- layers -->)."""
    text = open(os.path.join(ROOT, "docs", "architecture.md")).read()
    block = text.split("<!-- layers -->", 1)[1].split("```text", 1)[1].split("```", 1)[0]
    out = {}
    for line in block.strip().splitlines():
        m = re.match(r"layer (\d+): ([^(]*)", line)
        assert m, line
        for name in m.group(2).split():
            assert name not in out, "%s is drawn twice" % name
            out[name] = int(m.group(1))
    return out


def module_of(path):
    """The module a file of cpp/ belongs to: include/plunge/x.hpp and src/x.cpp
    are x; the front ends are their paths."""
    rel = os.path.relpath(path, CPP)
    if rel.startswith(("cli", "python")):
        return rel
    return os.path.splitext(os.path.basename(rel))[0]


def sources():
    for folder, _, files in os.walk(CPP):
        for f in files:
            if f.endswith((".hpp", ".cpp")):
                yield os.path.join(folder, f)


def includes(path):
    """The project's files a file includes: "plunge/x.hpp" or a src/ header "x.hpp"."""
    for m in re.finditer(r'^#include "([^"]+)"', open(path).read(), re.M):
        yield os.path.splitext(os.path.basename(m.group(1)))[0]


def test_every_file_is_drawn():
    drawn = layers()
    missing = sorted({module_of(p) for p in sources()} - set(drawn))
    assert not missing, "not in the layer drawing of docs/architecture.md: %s" % missing
    stale = sorted(set(drawn) - {module_of(p) for p in sources()})
    assert not stale, "drawn but not in cpp/: %s" % stale


def violations(paths, drawn):
    wrong = []
    for path in paths:
        own = drawn[module_of(path)]
        for name in includes(path):
            if drawn[name] > own:
                wrong.append("%s (layer %d) includes %s (layer %d)" % (os.path.relpath(path, ROOT), own, name,
                                                                       drawn[name]))
    return wrong


def test_no_file_includes_a_layer_above_its_own():
    wrong = violations(sources(), layers())
    assert not wrong, "\n".join(wrong)


def test_the_check_sees_a_layer_above(tmp_path):
    """The check itself: the data model including the pipeline is caught."""
    global CPP
    header = tmp_path / "include" / "plunge" / "types.hpp"
    header.parent.mkdir(parents=True)
    header.write_text('#pragma once\n#include "plunge/geometry.hpp"\n#include "plunge/plan.hpp"\n')
    saved, CPP = CPP, str(tmp_path)
    try:
        assert [w.endswith("includes plan (layer 9)") for w in violations([str(header)], layers())] == [True]
    finally:
        CPP = saved


@pytest.mark.parametrize("lower, upper", [("grower", "engagement"), ("lead_out", "motion"), ("clip", "polygon")])
def test_the_check_sees_a_callee_including_its_caller(tmp_path, lower, upper):
    """Within the real plunge mills and the polygons, what a module calls sits
    a layer below it: the callee including its caller's header (where options
    structs once lived) is caught."""
    global CPP
    header = tmp_path / "src" / (lower + ".hpp")
    header.parent.mkdir(parents=True)
    header.write_text('#pragma once\n#include "%s.hpp"\n' % upper)
    saved, CPP = CPP, str(tmp_path)
    try:
        drawn = layers()
        assert drawn[lower] < drawn[upper]
        assert [w.endswith("includes %s (layer %d)" % (upper, drawn[upper]))
                for w in violations([str(header)], drawn)] == [True]
    finally:
        CPP = saved


def test_the_public_api_stands_alone():
    """cpp/include/plunge/ holds what users of the library call, and nothing it
    includes is internal: a public header includes public headers only, and
    the front ends (CLI, Python module) use the public API alone."""
    public = {os.path.splitext(f)[0] for f in os.listdir(os.path.join(CPP, "include", "plunge"))}
    internal = {os.path.splitext(f)[0] for f in os.listdir(os.path.join(CPP, "src")) if f.endswith(".hpp")}
    assert {"plan", "types", "error"} <= public and not public & internal
    users = [os.path.join(CPP, "include", "plunge", f) for f in os.listdir(os.path.join(CPP, "include", "plunge"))]
    users += [os.path.join(CPP, "cli", "main.cpp"), os.path.join(CPP, "python", "module.cpp")]
    reaching = sorted((os.path.relpath(p, CPP), i) for p in users for i in includes(p) if i not in public)
    assert not reaching, reaching


def test_every_module_has_its_tests():
    """Each module of the library has its own GoogleTest file, or the page's
    table names the tests that cover it (and those exist); the table names
    only modules without a file of their own."""
    text = open(os.path.join(ROOT, "docs", "architecture.md")).read()
    table = text.split("<!-- tested-through -->", 1)[1].split("<!-- /tested-through -->", 1)[0]
    through = {}
    for module, tests in re.findall(r"^\| `([a-z_]+)` \|[^|]*\| (.*) \|$", table, re.M):
        through[module] = re.findall(r"`(tests/[^`]+)`", tests)
        assert through[module], module
        for t in through[module]:
            assert os.path.exists(os.path.join(ROOT, t)), (module, t)
    modules = {module_of(p) for p in sources() if not module_of(p).startswith(("cli/", "python/"))}
    # The public headers of the data model and the API are tested by every test.
    modules -= {"types", "error", "plan"}
    own = {m for m in modules if os.path.exists(os.path.join(ROOT, "tests", "cpp", "test_%s.cpp" % m))}
    assert sorted(modules - own - set(through)) == [], "modules with no tests named"
    assert sorted(set(through) & own) == [], "the table names modules that have their own file"
    assert sorted(set(through) - modules) == [], "the table names modules that do not exist"
