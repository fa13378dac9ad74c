"""The bundles' programs (resources/bundle.sh): fully static, and the same
plans as the planner built here, on Linux and on Windows under wine.

The bundles are dist/PlungeRough-{linux,windows}-x86_64.zip. Where one is
missing, or wine is, its cases are skipped, unless PLUNGE_TEST_PORTABLE=1
(CI's native run, tests/bundle/run.sh), which asks for all of them.

Golden inputs: every test shape and floor kind of test_program.py, and the
FreeCAD demo's floor as the addon meshes it (demo_mesh_input.py)."""
import json
import os
import shutil
import subprocess
import time
import zipfile

import pytest

from conftest import load_shape
from test_program import GOLDEN, golden, killed_while_planning, without_timings

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
DIST = os.path.join(ROOT, "dist")
REQUIRED = os.environ.get("PLUNGE_TEST_PORTABLE") == "1"
WINE = shutil.which("wine")


def need(what, present):
    if not present:
        if REQUIRED:
            pytest.fail("PLUNGE_TEST_PORTABLE=1 and %s is missing" % what)
        pytest.skip("%s is missing (sh resources/bundle.sh linux|windows)" % what)


def unzipped(platform, tmp_path_factory):
    path = os.path.join(DIST, "PlungeRough-%s-x86_64.zip" % platform)
    need(path, os.path.isfile(path))
    out = tmp_path_factory.mktemp(platform)
    with zipfile.ZipFile(path) as z:
        names = z.namelist()
        z.extractall(out)
    return out, names


@pytest.fixture(scope="module")
def linux(tmp_path_factory):
    out, names = unzipped("linux", tmp_path_factory)
    program = out / "PlungeRough" / "bin" / "plunge-rough"
    program.chmod(0o755)  # zipfile drops it, as the Addon Manager's unzip does
    return program, names


@pytest.fixture(scope="module")
def windows(tmp_path_factory):
    out, names = unzipped("windows", tmp_path_factory)
    need("wine", WINE)
    return out / "PlungeRough" / "bin" / "plunge-rough.exe", names


@pytest.fixture(scope="module")
def wine_env(tmp_path_factory):
    prefix = tmp_path_factory.mktemp("wineprefix")
    return dict(os.environ, WINEPREFIX=str(prefix), WINEDEBUG="-all", WINEDLLOVERRIDES="mscoree,mshtml=")


@pytest.fixture(scope="module")
def demo_mesh(build_dir):
    """The demo's plan input with its floor as the addon's mesh, made once in freecadcmd."""
    path = os.path.join(build_dir, "demo_mesh_input.json")
    if not os.path.exists(path):
        env = dict(os.environ, PLUNGE_DEMO_MESH_INPUT=path + ".part",
                   XDG_DATA_HOME=os.path.join(build_dir, "freecad-home", "demo_mesh", "data"),
                   XDG_CONFIG_HOME=os.path.join(build_dir, "freecad-home", "demo_mesh", "config"))
        run = subprocess.run(["freecadcmd", os.path.join(HERE, "demo_mesh_input.py")], env=env, capture_output=True,
                             text=True, timeout=600)
        assert os.path.exists(path + ".part"), run.stdout[-2000:] + run.stderr[-2000:]
        os.replace(path + ".part", path)
    with open(path) as f:
        return json.load(f)


def inputs(demo_mesh):
    out = {name: golden(name) for name in GOLDEN}
    out["demo mesh"] = demo_mesh
    return out


def plan_with(argv, data, env=None, svg=True):
    run = subprocess.run(argv + ["call"], input=json.dumps({"call": "plan", "input": data, "svg": svg}),
                         capture_output=True, text=True, env=env, timeout=600)
    assert run.returncode == 0, run.stderr[-2000:]
    return json.loads(run.stdout)


def check_bundle(names, program):
    """One folder PlungeRough/: the addon as FreeCAD's Mod folder wants it, the
    program in bin/, no compiled Python module."""
    assert {n.split("/")[0] for n in names} == {"PlungeRough"}
    for f in ("Init.py", "InitGui.py", "package.xml", "freecad_plugin/PlungeRough.py", "freecad_plugin/planner.py",
              "freecad_plugin/floor_mesh.py", "resources/panels/PlungeRoughEdit.ui", "bin/" + program):
        assert "PlungeRough/" + f in names, f
    assert not [n for n in names if n.endswith((".so", ".pyd")) or ".so." in n]


def test_the_linux_bundle_holds_a_fully_static_program(linux):
    program, names = linux
    check_bundle(names, "plunge-rough")
    headers = subprocess.run(["readelf", "-lW", str(program)], capture_output=True, text=True).stdout
    dynamic = subprocess.run(["readelf", "-d", str(program)], capture_output=True, text=True).stdout
    assert "INTERP" not in headers and "NEEDED" not in dynamic
    run = subprocess.run([str(program), "call"], input='{"call": "about"}', capture_output=True, text=True, env={})
    about = json.loads(run.stdout)
    assert about["system"] == "linux" and "brep" not in about["floors"] and "mesh" in about["floors"]


def test_the_windows_bundle_imports_only_windows_own_dlls(windows):
    program, names = windows
    check_bundle(names, "plunge-rough.exe")
    dump = subprocess.run(["x86_64-w64-mingw32-objdump", "-p", str(program)], capture_output=True, text=True).stdout
    dlls = {line.split("DLL Name:")[1].strip().lower() for line in dump.splitlines() if "DLL Name:" in line}
    assert dlls and dlls <= {"kernel32.dll", "msvcrt.dll", "shell32.dll", "user32.dll", "advapi32.dll"}, dlls


def test_the_linux_program_plans_as_the_build_here(linux, cli, demo_mesh):
    program, _ = linux
    for name, data in inputs(demo_mesh).items():
        ours = plan_with([cli], data)
        assert without_timings(plan_with([str(program)], data)) == without_timings(ours), name


def differences(a, b, where="plan", tolerance=1e-9):
    """Where two plans differ: in kind, length, text or key, or in a number by
    more than `tolerance` (mm, or its fraction)."""
    if isinstance(a, float) or isinstance(b, float):
        ok = isinstance(a, (int, float)) and isinstance(b, (int, float)) and abs(a - b) <= tolerance * max(1, abs(a))
        return [] if ok else ["%s: %r != %r" % (where, a, b)]
    if isinstance(a, dict) and isinstance(b, dict):
        if set(a) != set(b):
            return ["%s: keys %s" % (where, sorted(set(a) ^ set(b)))]
        return [d for k in a for d in differences(a[k], b[k], "%s.%s" % (where, k), tolerance)]
    if isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            return ["%s: %d != %d items" % (where, len(a), len(b))]
        return [d for k, (x, y) in enumerate(zip(a, b)) for d in differences(x, y, "%s[%d]" % (where, k), tolerance)]
    return [] if a == b else ["%s: %r != %r" % (where, a, b)]


def test_the_windows_program_plans_as_the_linux_program(linux, windows, wine_env, demo_mesh):
    """The same plunges, order, tools, statistics, summary and pictures; the
    numbers may differ in their last bits (about 1e-15), where Windows' math
    library rounds otherwise than glibc's."""
    for name, data in inputs(demo_mesh).items():
        on_linux = plan_with([str(linux[0])], data)
        on_windows = plan_with([WINE, str(windows[0])], data, env=wine_env)
        assert not differences(without_timings(on_windows), without_timings(on_linux)), name


def test_the_windows_program_from_and_to_paths_with_any_character(windows, wine_env, tmp_path):
    folder = tmp_path / "Plänè ü 計画"
    folder.mkdir()
    program = folder / "plunge-rough.exe"
    shutil.copy(windows[0], program)
    source, output = folder / "poche é.json", folder / "plan ü.json"
    source.write_text(json.dumps(load_shape("convex")), encoding="utf-8")
    run = subprocess.run([WINE, str(program), "plan", str(source), "-o", str(output), "--svg", str(folder / "é.svg")],
                         capture_output=True, text=True, env=wine_env, timeout=300)
    assert run.returncode == 0, run.stderr
    assert json.loads(output.read_text())["plunges"] and (folder / "é-stock.svg").exists()
    assert plan_with([WINE, str(program)], load_shape("convex"), env=wine_env, svg=False)["plunges"]


def test_a_kill_stops_the_windows_program(windows, wine_env):
    took, code = killed_while_planning([WINE, str(windows[0])], env=wine_env)
    assert took < 1.0 and code == -9
    # Nothing of it goes on planning: its process is gone from wine.
    time.sleep(0.5)
    left = subprocess.run(["pgrep", "-f", "plunge-rough.exe"], capture_output=True, text=True).stdout.split()
    assert not left, left
