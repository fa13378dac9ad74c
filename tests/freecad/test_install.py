"""The installed addon (cmake --install ... --component freecad_addon, as
resources/install_addon.sh does) loads in a fresh FreeCAD profile: FreeCAD runs
its Init.py, the op registers with the setup sheets, and the planner module next
to it plans, all from the Mod folder and not from the source or build tree."""
import json
import os
import re
import subprocess

from conftest import BUILD, ROOT

CHECK = r"""
import json, sys, FreeCAD
import freecad_plugin, plunge
from freecad_plugin.compat import PathSetupSheet
from freecad_plugin import PlungeRough, planner
plan = planner.planner().plan({"version": 1, "boundary": [[0, 0], [60, 0], [60, 40], [0, 40]],
    "tools": [{"id": 1, "diameter": 16}, {"id": 2, "diameter": 6}], "top_z": 0, "safe_z": 5,
    "floor": {"z": -10}})
print("RESULT=" + json.dumps({"plugin": freecad_plugin.__file__, "plunge": plunge.__file__,
    "planner": planner.planner().name,
    "registered": "PlungeRough" in PathSetupSheet._RegisteredOps, "plunges": len(plan["plunges"]),
    "core_coverage": plan["stats"]["core_coverage"]}))
"""


def check_plans(tmp_path, env):
    """CHECK run in freecadcmd with env's profile: its result and all it printed."""
    check = tmp_path / "check.py"  # a file: FreeCAD 1.1 ends on a -c argument of 256 characters
    check.write_text(CHECK)
    run = subprocess.run(["freecadcmd", str(check)], cwd=str(tmp_path), env=env, capture_output=True, text=True,
                         timeout=300)
    lines = [l for l in run.stdout.replace("\r", "\n").splitlines() if l.startswith("RESULT=")]
    assert lines, run.stdout[-2000:] + run.stderr[-2000:]
    return json.loads(lines[0][len("RESULT="):]), run.stdout + run.stderr


def test_installed_addon_loads_and_plans(tmp_path):
    mod = tmp_path / "data" / "FreeCAD" / "Mod"
    subprocess.run(["cmake", "--install", BUILD, "--component", "freecad_addon", "--prefix", str(mod)],
                   check=True, capture_output=True)
    installed = mod / "PlungeRough"
    for name in ("Init.py", "InitGui.py", "package.xml", "freecad_plugin/PlungeRough.py",
                 "freecad_plugin/companions.py", "freecad_plugin/planner.py", "resources/icons/PlungeRough.svg",
                 "resources/panels/PlungeRoughEdit.ui", "resources/tools/plungemill.svg",
                 "freecad_plugin/plunge_mill.py", "freecad_plugin/tools.py"):
        assert (installed / name).is_file(), name
    env = dict(os.environ, XDG_DATA_HOME=str(tmp_path / "data"), XDG_CONFIG_HOME=str(tmp_path / "config"))
    env.pop("PYTHONPATH", None)
    result, _ = check_plans(tmp_path, env)
    assert result["plugin"].startswith(str(installed))
    assert result["plunge"].startswith(str(installed))
    # It plans out of FreeCAD's process, through the program in its bin/.
    assert ", program %s (the addon's bin)" % (installed / "bin" / "plunge-rough") in result["planner"]
    assert result["registered"]
    assert result["plunges"] > 0 and result["core_coverage"] > 0.9999


def test_package_metadata():
    """package.xml is what the Addon Manager reads: it must parse, carry the
    project's version and point at files that exist."""
    import FreeCAD
    meta = FreeCAD.Metadata(os.path.join(ROOT, "package.xml"))
    assert meta.Name == "PlungeRough"
    with open(os.path.join(ROOT, "CMakeLists.txt")) as f:
        assert "VERSION %s " % meta.Version in f.read()
    assert os.path.isfile(os.path.join(ROOT, meta.Icon))
    workbenches = meta.Content["workbench"]
    assert [w.Subdirectory for w in workbenches] == ["./"]
    assert os.path.isfile(os.path.join(ROOT, workbenches[0].Subdirectory, "InitGui.py"))
    # The FreeCAD running this test is one the metadata says was tested, and not
    # older than its minimum.
    running = tuple(int(v) for v in FreeCAD.Version()[:2])
    minimum = tuple(int(v) for v in workbenches[0].FreeCADMin.split(".")[:2])
    assert running >= minimum
    tested = re.findall(r"\d+\.\d+", meta.Description.split("Tested with FreeCAD ")[1].split("(")[0])
    assert "%d.%d" % running in tested, tested


MODDIR = r"""
import FreeCAD
print("MODDIR=" + FreeCAD.getUserAppDataDir() + "Mod")
"""


def test_a_clone_into_mod_says_how_to_build_the_planner_and_then_plans(tmp_path):
    """FreeCAD's Addon Manager clones the repository into the user's Mod folder:
    the sources alone. FreeCAD started headless says that the planner is
    missing, with the one command that builds and installs it; that command
    run, the clone plans and has its plunge-mill bits. The command builds the
    planner only where PLUNGE_TEST_ADDON_BUILD=1 (one of CI's fresh-machine
    runs: minutes); elsewhere the clone's build/ is this build tree, and the
    command runs without --build."""
    import shutil
    env = dict(os.environ, XDG_DATA_HOME=str(tmp_path / "data"), XDG_CONFIG_HOME=str(tmp_path / "config"))
    env.pop("PYTHONPATH", None)

    def freecad(script):
        path = tmp_path / "script.py"
        path.write_text(script)
        run = subprocess.run(["freecadcmd", str(path)], cwd=str(tmp_path), env=env, capture_output=True, text=True,
                             timeout=300)
        return run.stdout.replace("\r", "\n") + run.stderr.replace("\r", "\n")

    mod = [l for l in freecad(MODDIR).splitlines() if l.startswith("MODDIR=")][0][len("MODDIR="):]
    clone = os.path.join(mod, "PlungeRough")
    shutil.copytree(ROOT, clone, ignore=shutil.ignore_patterns(
        ".git", "build", "build-*", "out", "Tools", "__pycache__", ".pytest_cache", "*.so", "*.so.*"))
    said = freecad(MODDIR)
    m = re.search(r"PlungeRough: the planner is not installed: .*: get PlungeRough-linux-x86_64.zip .*; or build and "
                  r"install it for this FreeCAD, as root on Debian: (sh '[^']+' --build)", said)
    assert m, said[-3000:]
    command = m.group(1)
    assert command == "sh '%s/resources/install_addon.sh' --build" % clone
    # What FreeCAD's GUI does once it has started (InitGui.py): the bits made
    # in the clone and registered, once.
    made = freecad("from freecad_plugin import plunge_mill\n"
                   "print('BITS=%d,%d' % (len(plunge_mill.ensure_installed()), len(plunge_mill.ensure_installed())))")
    counts = re.search(r"BITS=(\d+),(\d+)", made)
    assert counts and int(counts.group(1)) > 0 and counts.group(2) == "0", made[-2000:]
    assert "the plunge-mill tool bits are in %s" % os.path.join(clone, "Tools") in made
    if os.environ.get("PLUNGE_TEST_ADDON_BUILD") != "1":
        os.symlink(BUILD, os.path.join(clone, "build"))
        command = command[:-len(" --build")]
    run = subprocess.run(["sh", "-c", command], env=env, capture_output=True, text=True, timeout=3600)
    assert run.returncode == 0, run.stdout[-2000:] + run.stderr[-2000:]
    result, said = check_plans(tmp_path, env)
    assert result["plugin"].startswith(clone) and result["plunge"].startswith(clone)
    assert ", program %s (the addon's bin)" % os.path.join(clone, "bin", "plunge-rough") in result["planner"]
    assert result["plunges"] > 0 and result["core_coverage"] > 0.9999
    assert "not installed" not in said  # said no more
    bits = os.listdir(os.path.join(clone, "Tools", "Bit"))
    assert bits and all(b.endswith(".fctb") for b in bits)
