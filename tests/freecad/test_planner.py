"""The planner as the addon finds and runs it (freecad_plugin/planner.py): in
order, the environment's command line, the preference, the addon's bin/ (its
execute bit given back) and the module; the program stopped within a second
of Esc; a planner that crashes or is killed from outside said in the summary,
with FreeCAD up and the operation planned again at the next recompute."""
import os
import shutil
import signal
import stat
import subprocess
import sys
import threading
import time

import FreeCAD
import pytest

import parts
from conftest import BUILD, build_op
from freecad_plugin import PlungeRough, companions, planner

PROGRAM = os.path.join(BUILD, "cpp", "plunge-rough")


@pytest.fixture
def fresh(monkeypatch, tmp_path):
    """No planner found yet, no preference, an addon folder of the test's own."""
    monkeypatch.setattr(planner, "_found", {})
    monkeypatch.delenv(planner.ENVIRONMENT, raising=False)
    addon = tmp_path / "PlungeRough"
    (addon / "bin").mkdir(parents=True)
    monkeypatch.setattr(planner, "ADDON", str(addon))
    prefs = FreeCAD.ParamGet(planner.PREFERENCES)
    yield addon
    prefs.RemString(planner.PREFERENCE)


def test_found_in_order(fresh, monkeypatch, tmp_path):
    prefs = FreeCAD.ParamGet(planner.PREFERENCES)
    bundled = fresh / "bin" / "plunge-rough"
    shutil.copy(PROGRAM, bundled)
    os.chmod(bundled, 0o644)  # as a ZIP install leaves it
    # 3. the addon's bin/, its execute bit given back
    found = planner.planner()
    assert (found.argv, found.where) == ([str(bundled)], "the addon's bin")
    assert os.stat(bundled).st_mode & stat.S_IXUSR
    # 2. the preference, before the addon's bin/
    other = tmp_path / "elsewhere" / "plunge-rough"
    other.parent.mkdir()
    shutil.copy(PROGRAM, other)
    prefs.SetString(planner.PREFERENCE, str(other))
    found = planner.planner()
    assert (found.argv, found.where) == ([str(other)], "the preference PlannerPath")
    prefs.SetString(planner.PREFERENCE, str(tmp_path / "nothing"))
    with pytest.raises(ValueError, match="the planner set in the preferences \\(PlannerPath\\) is not a program"):
        planner.planner()
    # 1. the environment's command line, before everything
    monkeypatch.setenv(planner.ENVIRONMENT, "env PLUNGE_X=1 '%s'" % other)
    found = planner.planner()
    assert (found.argv, found.where) == (["env", "PLUNGE_X=1", str(other)], planner.ENVIRONMENT)
    assert found.plan({"version": 1, "boundary": [[0, 0], [50, 0], [50, 30], [0, 30]], "tools": [{"diameter": 10}],
                       "top_z": 0, "safe_z": 5, "floor": {"z": -5}})["plunges"]
    # 4. the module, last
    monkeypatch.delenv(planner.ENVIRONMENT)
    prefs.RemString(planner.PREFERENCE)
    os.remove(bundled)
    assert isinstance(planner.planner(), planner.Module)


def test_no_planner_names_the_bundle_to_get(fresh, monkeypatch):
    monkeypatch.setitem(sys.modules, "plunge", None)  # import plunge fails
    with pytest.raises(ValueError) as e:
        planner.planner()
    assert "the planner is not installed: no plunge-rough in %s/bin" % fresh in str(e.value)
    assert "get PlungeRough-linux-x86_64.zip from PlungeRough's releases and unzip it into FreeCAD's Mod folder" \
        in str(e.value)


@pytest.mark.parametrize("system, machine, tag", [
    ("Linux", "x86_64", "linux-x86_64"), ("Linux", "aarch64", "linux-aarch64"), ("Linux", "arm64", "linux-aarch64"),
    ("Windows", "AMD64", "windows-x86_64"), ("Darwin", "arm64", "macos-arm64"), ("Darwin", "x86_64", "macos-x86_64"),
    ("Windows", "ARM64", None), ("Linux", "ppc64le", None), ("FreeBSD", "amd64", None)])
def test_each_system_and_machine_has_its_folder(system, machine, tag):
    assert planner.platform_tag(system, machine) == tag


def test_the_universal_zip_gives_this_machine_its_own_program(fresh, monkeypatch):
    """bin/<os>-<arch>/ of this machine first, then bin/ itself; on a machine
    none is built for, the message names the system and machine found."""
    here = planner.platform_tag()
    assert here == "linux-x86_64"  # the machines the suite runs on
    for tag in planner.PLATFORMS:
        (fresh / "bin" / tag).mkdir()
        name = "plunge-rough.exe" if tag.startswith("windows") else "plunge-rough"
        target = fresh / "bin" / tag / name
        if tag == here:
            shutil.copy(PROGRAM, target)
            os.chmod(target, 0o644)  # the Addon Manager's unzip drops the execute bit
        else:
            target.write_bytes(b"not this machine's")
    shutil.copy(PROGRAM, fresh / "bin" / "plunge-rough")
    found = planner.planner()
    assert found.argv == [str(fresh / "bin" / here / "plunge-rough")]
    assert found.plan({"version": 1, "boundary": [[0, 0], [50, 0], [50, 30], [0, 30]], "tools": [{"diameter": 10}],
                       "top_z": 0, "safe_z": 5, "floor": {"z": -5}})["plunges"]
    monkeypatch.setattr(planner, "_found", {})
    monkeypatch.setattr(planner.platform, "machine", lambda: "riscv64")
    os.remove(fresh / "bin" / "plunge-rough")
    monkeypatch.setitem(sys.modules, "plunge", None)
    with pytest.raises(ValueError) as e:
        planner.planner()
    assert "the planner is not built for this system and machine (Linux, riscv64)" in str(e.value)
    assert "linux-x86_64, linux-aarch64, windows-x86_64, macos-arm64, macos-x86_64 only" in str(e.value)


class Recorder:
    """subprocess.Popen as the planner calls it, each process kept."""

    def __init__(self, monkeypatch):
        self.procs = []
        real = subprocess.Popen

        def popen(*args, **kwargs):
            proc = real(*args, **kwargs)
            self.procs.append(proc)
            return proc

        monkeypatch.setattr(planner.subprocess, "Popen", popen)


def slow_pocket(doc):
    """A pocket that takes the program seconds to plan (a 10 % engagement limit)."""
    job, op, tcs = build_op(doc, parts.islands_part(), sculptured=False)
    op.MaxEngagement = 10.0
    doc.recompute()
    return job, op, tcs


def test_esc_stops_the_program_within_a_second(doc, fresh, monkeypatch):
    monkeypatch.setenv(planner.ENVIRONMENT, PROGRAM)
    procs = Recorder(monkeypatch)
    job, op, tcs = slow_pocket(doc)
    assert PlungeRough.plan_of(op)
    aborted, calls = [], []

    class Indicator:  # the user presses Esc, and confirms, while the planner works
        def start(self, text, steps):
            pass

        def next(self, can_abort=False):
            calls.append(1)
            if len(calls) == 2:
                aborted.append((time.monotonic(), procs.procs[-1].poll() is None))
                raise FreeCAD.Base.FreeCADAbort("Aborting...")

        def stop(self):
            pass

    monkeypatch.setattr(FreeCAD.Base, "ProgressIndicator", Indicator)
    op.touch()
    doc.recompute()
    done = time.monotonic()
    assert aborted and aborted[0][1], "the plan ended before Esc"
    assert done - aborted[0][0] < 1.0
    assert procs.procs and all(p.poll() is not None for p in procs.procs)  # no planner left running
    assert op.Summary.startswith("planning cancelled")
    assert not [c for c in op.Path.Commands if c.Name == "G1"]


def test_a_cancel_is_not_bad_input(doc, fresh, monkeypatch):
    """A progress that says no: the program stops, planner.Cancelled (no
    ValueError handler takes it), and the operation says it was cancelled, in
    the report view as a note, not an error."""
    monkeypatch.setenv(planner.ENVIRONMENT, PROGRAM)
    procs = Recorder(monkeypatch)
    job, op, tcs = slow_pocket(doc)
    calls = []
    with pytest.raises(planner.Cancelled) as e:
        planner.planner().plan(companions.plan_data(op)["input"], progress=lambda f, s: calls.append(f) or len(calls) < 2)
    assert not isinstance(e.value, ValueError) and "planning cancelled" in str(e.value)
    assert all(p.poll() is not None for p in procs.procs)
    said = []
    monkeypatch.setattr(PlungeRough, "_report", lambda obj, text, error=True: said.append((text, error)))
    monkeypatch.setattr(planner.PlanProgress, "__call__", lambda self, f, s: False)
    op.touch()
    doc.recompute()
    assert said and said[-1][0].startswith("planning cancelled") and said[-1][1] is False, said
    assert not [c for c in op.Path.Commands if c.Name == "G1"]


def crashing_planner(tmp_path, how):
    """A planner that answers as the real one does, but asked to plan writes
    its process id to planning.pid and does `how` (replacing itself)."""
    script = tmp_path / "planner.sh"
    script.write_text("#!/bin/sh\nrequest=$(cat)\ncase $request in *'\"call\": \"plan\"'*) echo $$ > '%s'; %s;; esac\n"
                      "printf '%%s' \"$request\" | exec '%s' call\n" % (tmp_path / "planning.pid", how, PROGRAM))
    script.chmod(0o755)
    return str(script)


@pytest.mark.parametrize("how,said", [("kill -SEGV $$", "crashed (SIGSEGV)"),
                                      ("exec sleep 30", "was stopped (SIGKILL)")])
def test_a_planner_that_crashes_or_is_killed_is_said_and_planned_again(doc, fresh, monkeypatch, tmp_path, how, said):
    job, op, tcs = build_op(doc, parts.islands_part(), sculptured=False)
    monkeypatch.setenv(planner.ENVIRONMENT, crashing_planner(tmp_path, how))
    pid = tmp_path / "planning.pid"

    def kill_the_plan():  # from outside, as a user or the system would
        deadline = time.monotonic() + 20
        while time.monotonic() < deadline and not pid.exists():
            time.sleep(0.05)
        time.sleep(0.3)
        os.kill(int(pid.read_text()), signal.SIGKILL)

    if how.startswith("exec sleep"):
        threading.Thread(target=kill_the_plan, daemon=True).start()
    start = time.monotonic()
    op.touch()
    doc.recompute()
    assert time.monotonic() - start < 10
    assert said in op.Summary and "nothing is cut until it plans again (the next recompute)" in op.Summary
    assert op.Summary.startswith("the planner %s " % os.environ[planner.ENVIRONMENT])
    assert not [c for c in op.Path.Commands if c.Name == "G1"]
    # FreeCAD is up, and the next recompute plans with a planner that works.
    assert "Touched" in op.State
    monkeypatch.setenv(planner.ENVIRONMENT, PROGRAM)
    doc.recompute()
    assert PlungeRough.plan_of(op) and [c for c in op.Path.Commands if c.Name == "G1"]
