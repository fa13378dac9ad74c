"""The planner as the addon uses it, and FreeCAD's progress indicator reporting
(and cancelling) a plan.

The planner is a program the addon runs for each call (`plunge-rough call`:
JSON in, JSON out, progress on stderr, docs/cli.md), out of FreeCAD's
process: a crash of the planner cannot take FreeCAD down, and Esc stops it at
once. It is looked for, in this order:

1. the environment variable PLUNGE_ROUGH_PLANNER, a command line (a test runs
   `wine /path/plunge-rough.exe` so);
2. the preference PlannerPath (Preferences/Mod/PlungeRough), a program's path;
3. the addon's own bin/: bin/<os>-<arch>/ for this system and machine (the
   universal zip holds every platform's program so: PLATFORMS), then bin/
   itself (a platform's own zip, or the README's install);
4. the compiled module `plunge` beside the addon, planning in FreeCAD's process.

App side: never imports GUI code.
"""
import contextlib
import json
import os
import platform
import shlex
import signal
import stat
import subprocess
import threading

import FreeCAD

from freecad_plugin.constants import ADDON

ENVIRONMENT = "PLUNGE_ROUGH_PLANNER"
PREFERENCES = "User parameter:BaseApp/Preferences/Mod/PlungeRough"
PREFERENCE = "PlannerPath"
PROGRAM = "plunge-rough.exe" if os.name == "nt" else "plunge-rough"

# What FreeCAD raises when the user aborts (not an Exception).
ABORT = getattr(FreeCAD.Base, "FreeCADAbort", KeyboardInterrupt)


class Cancelled(Exception):
    """The plan was cancelled (its progress callback returned False): not bad
    input, so not a ValueError; the module's own plunge.Cancelled becomes it."""


class PlannerFailed(RuntimeError):
    """The planner program crashed, was killed or could not be started: said in
    the report view, nothing is cut, and the operation plans again at the next
    recompute."""


# The platforms a program is built for (resources/bundle.sh): the universal
# zip's bin/<os>-<arch>/ folders, and the platforms' own zips' names.
PLATFORMS = ("linux-x86_64", "linux-aarch64", "windows-x86_64", "macos-arm64", "macos-x86_64")
_SYSTEMS = {"linux": "linux", "windows": "windows", "darwin": "macos"}
# What platform.machine() says for the same architecture on each system.
_MACHINES = {"x86_64": "x86_64", "amd64": "x86_64", "x64": "x86_64", "aarch64": "aarch64", "arm64": "aarch64",
             "armv8l": "aarch64"}


def platform_tag(system=None, machine=None):
    """This system's and machine's folder in the universal zip's bin/
    (PLATFORMS), or None where no program is built for them. macOS calls its
    ARM arm64, Linux aarch64: the names of the folders follow each system's."""
    system = (system if system is not None else platform.system()).lower()
    machine = (machine if machine is not None else platform.machine()).lower()
    arch = _MACHINES.get(machine)
    os_ = _SYSTEMS.get(system)
    if os_ == "macos" and arch == "aarch64":
        arch = "arm64"
    tag = "%s-%s" % (os_, arch)
    return tag if tag in PLATFORMS else None


def bundle_name():
    """The platform's own zip for this machine, or None where none is built."""
    tag = platform_tag()
    return "PlungeRough-%s.zip" % tag if tag else None


def bundled_program(addon=None):
    """The addon's own program for this machine (the module's docstring, 3.):
    bin/<os>-<arch>/, then bin/; None when there is none."""
    addon = addon or ADDON
    tag = platform_tag()
    for path in ([os.path.join(addon, "bin", tag, PROGRAM)] if tag else []) + [os.path.join(addon, "bin", PROGRAM)]:
        if _executable(path):
            return path
    return None


def _built_for(addon):
    """The platforms whose programs the addon's bin/ holds (a universal zip's)."""
    folder = os.path.join(addon, "bin")
    return [t for t in PLATFORMS if os.path.isfile(os.path.join(folder, t, "plunge-rough.exe" if t.startswith("windows")
                                                                 else "plunge-rough"))]


def install_command(addon=None):
    """The one command that builds the planner and installs it (and the
    plunge-mill bits) for this FreeCAD, from a clone of the repository (an
    Addon Manager install is one) on Debian or Ubuntu; None for an installed
    copy, which has no sources to build from, and away from Debian."""
    addon = addon or ADDON
    if not os.path.exists(os.path.join(addon, "resources", "setup.sh")) or not os.path.exists("/etc/debian_version"):
        return None
    return "sh '%s/resources/install_addon.sh' --build" % addon


def missing_planner_message(error=None, addon=None):
    """What the user reads when no planner is found: the bundle to get for
    this platform and where it goes, and on Debian or Ubuntu the build command."""
    addon = addon or ADDON
    why = " (%s)" % error if error else ""
    bundle = bundle_name()
    built = _built_for(addon)
    if built and not platform_tag():
        # A universal zip on a system or machine no program is built for.
        message = ("the planner is not built for this system and machine (%s, %s): %s/bin holds programs for %s "
                   "only; build the planner from source (docs/install.md, \"From source\") and set its path in "
                   "the preference %s" % (platform.system(), platform.machine(), addon, ", ".join(built),
                                          PREFERENCE))
        command = install_command(addon)
        return message + ("; or build and install it for this FreeCAD, as root on Debian: %s" % command
                          if command else "")
    if bundle:
        get = ("get %s from PlungeRough's releases and unzip it into FreeCAD's Mod folder (%s), replacing this "
               "folder: it holds the addon and its planner" % (bundle, os.path.dirname(addon)))
    else:
        get = "build the planner from source (docs/install.md: untested on this system)"
    message = "the planner is not installed: no %s in %s/bin and no plunge module beside the addon%s: %s" % (
        PROGRAM, addon, why, get)
    command = install_command(addon)
    if command:
        message += "; or build and install it for this FreeCAD, as root on Debian: %s" % command
    return message


# ---------------------------------------------------------------- the program

def _run(argv, request, progress=None):
    """One call of the planner program: the request's JSON on its stdin, its
    answer's on stdout, "progress FRACTION STAGE" lines on stderr. progress is
    called about every 0.1 s; when it raises (the user's abort) or returns
    False, the program is killed. A ValueError carries the planner's own
    message for bad input; PlannerFailed says how the program ended otherwise."""
    flags = getattr(subprocess, "CREATE_NO_WINDOW", 0)  # no console window flashing up on Windows
    try:
        proc = subprocess.Popen(argv, stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                creationflags=flags)
    except OSError as e:
        raise PlannerFailed("the planner %s could not be started: %s" % (argv[0], e.strerror or e))
    payload = json.dumps(request).encode("utf-8")
    out, messages, latest = [], [], [0.0, "starting the planner"]

    def write():
        try:
            proc.stdin.write(payload)
            proc.stdin.close()
        except OSError:  # it ended before reading everything: its exit says why
            pass

    def read_errors():
        for raw in proc.stderr:
            line = raw.decode("utf-8", "replace").rstrip("\r\n")
            if line.startswith("progress "):
                parts = line.split(" ", 2)
                try:
                    latest[:] = [float(parts[1]), parts[2] if len(parts) > 2 else ""]
                except ValueError:
                    messages.append(line)
            elif line:
                messages.append(line)

    threads = [threading.Thread(target=write, daemon=True), threading.Thread(target=read_errors, daemon=True),
               threading.Thread(target=lambda: out.append(proc.stdout.read()), daemon=True)]
    for t in threads:
        t.start()
    try:
        while proc.poll() is None:
            if progress is not None and progress(latest[0], latest[1]) is False:
                raise Cancelled("planning cancelled")
            try:
                proc.wait(timeout=0.1)
            except subprocess.TimeoutExpired:
                pass
    finally:
        if proc.poll() is None:  # cancelled (Esc, Ctrl+C): stopped at once
            proc.kill()
            proc.wait()
        # Its answer is read to the end; what else it left (a child of a
        # wrapper still holding the pipes) is not waited for.
        for t in threads:
            t.join(timeout=30 if proc.returncode == 0 else 0.5)
    code = proc.returncode
    if code == 0:
        try:
            return json.loads(out[0].decode("utf-8") if out else "")
        except ValueError:
            raise PlannerFailed("the planner %s gave an answer that is not JSON" % argv[0])
    said = [m for m in messages if m.startswith("plunge-rough: ")]
    if code == 2 and said:  # bad input, in the planner's own words
        raise ValueError(said[-1][len("plunge-rough: error: "):] if said[-1].startswith("plunge-rough: error: ")
                         else said[-1])
    raise PlannerFailed("the planner %s %s%s" % (argv[0], _ended(code), (": " + messages[-1]) if messages else ""))


def _ended(code):
    """How a program ended, for people."""
    if code < 0:
        try:
            name = signal.Signals(-code).name
        except ValueError:
            name = "signal %d" % -code
        return "crashed (%s)" % name if -code in (4, 6, 7, 8, 11) else "was stopped (%s)" % name
    if os.name == "nt" and code >= 0xC0000000:
        return "crashed (Windows exception 0x%08X)" % code
    return "failed with exit status %d" % code


class Program:
    """The planner program, run once per call."""

    def __init__(self, argv, where):
        self.argv = list(argv)
        self.where = where  # how it was found, for the report view
        self._about = None

    def about(self):
        if self._about is None:
            self._about = _run(self.argv + ["call"], {"call": "about"})
        return self._about

    @property
    def name(self):
        return "%s, program %s (%s)" % (self.about().get("planner", "PlungeRough"), " ".join(self.argv), self.where)

    @property
    def floors(self):
        return self.about().get("floors", [])

    def plan(self, data, svg=False, progress=None):
        return _run(self.argv + ["call"], {"call": "plan", "input": data, "svg": bool(svg)}, progress)

    def start_hole_tools(self, tools):
        return {int(k): v for k, v in _run(self.argv + ["call"], {"call": "start_hole_tools", "tools": tools}).items()}

    def sweep(self, material, tool, moves, progress=None):
        return _run(self.argv + ["call"], {"call": "sweep", "material": material, "tool": tool,
                                           "moves": [list(m) for m in moves]}, progress)["top"]


class Module:
    """The compiled module beside the addon, planning in FreeCAD's process."""

    def __init__(self, module):
        self.module = module
        info = module.about()
        self.floors = info["floors"]
        self.name = "%s, module %s" % (info["planner"], module.__file__)

    @contextlib.contextmanager
    def _cancels(self):
        """The module's plunge.Cancelled as the addon's Cancelled, as the program's."""
        try:
            yield
        except self.module.Cancelled as e:
            raise Cancelled(str(e)) from None

    def plan(self, data, svg=False, progress=None):
        with self._cancels():
            return self.module.plan(data, svg=svg, progress=progress)

    def start_hole_tools(self, tools):
        return self.module.start_hole_tools(tools)

    def sweep(self, material, tool, moves, progress=None):
        with self._cancels():
            return self.module.sweep(material, tool, moves, progress)


def _executable(path):
    """path, with the execute bit a ZIP install loses given back; False when it
    is no file."""
    if not os.path.isfile(path):
        return False
    if os.name != "nt" and not os.access(path, os.X_OK):
        try:
            os.chmod(path, os.stat(path).st_mode | stat.S_IXUSR | stat.S_IXGRP | stat.S_IXOTH)
        except OSError:
            return False
    return True


_found = {}


def planner():
    """The planner, where users put it (the module's docstring); ValueError
    saying what to install when there is none, or what is wrong with the one
    named by the environment or the preference."""
    command = os.environ.get(ENVIRONMENT, "").strip()
    if command:
        return _cached(_split(command), ENVIRONMENT)
    path = FreeCAD.ParamGet(PREFERENCES).GetString(PREFERENCE, "").strip()
    if path:
        if not _executable(path):
            raise ValueError("the planner set in the preferences (%s) is not a program: %s" % (PREFERENCE, path))
        return _cached([path], "the preference %s" % PREFERENCE)
    bundled = bundled_program()
    if bundled:
        return _cached([bundled], "the addon's bin")
    try:
        import plunge
    except ImportError as e:
        raise ValueError(missing_planner_message(e))
    return _cached(None, plunge)


def _split(command):
    """A command line's words: as a POSIX shell splits them, or on Windows at
    spaces outside double quotes (backslashes are a path's, not escapes)."""
    if os.name != "nt":
        return shlex.split(command)
    return [w[1:-1] if len(w) > 1 and w[0] == w[-1] == '"' else w for w in shlex.split(command, posix=False)]


def _cached(argv, where):
    """One Program per command line (its "about" asked once), one Module."""
    key = tuple(argv) if argv is not None else "module"
    if key not in _found:
        _found[key] = Program(argv, where) if argv is not None else Module(where)
    return _found[key]


def is_abort(error):
    """Whether an exception is the user's abort: FreeCAD's own, the progress
    indicator's RuntimeError when it is the outermost one (a recompute with
    the "can abort" preference off), or a progress that said no (Cancelled)."""
    return isinstance(error, (ABORT, Cancelled)) or (isinstance(error, RuntimeError)
                                                      and "abort progress indicator" in str(error))


class PlanProgress:
    """The planner's progress in FreeCAD's progress indicator (the GUI's status
    bar, which keeps the GUI drawn while planning). Esc asks whether to abort;
    aborting cancels the plan. Inside a recompute the document's own indicator
    is the outermost one and ignores this one's steps (FreeCAD 0.20 to 1.1):
    FreeCAD.checkAbort() is what processes events and raises the abort there,
    on every FreeCAD version (in freecadcmd it does nothing)."""

    def __init__(self, label):
        self.label = label
        self.stage = None
        self.indicator = FreeCAD.Base.ProgressIndicator()
        self.running = False

    def __call__(self, fraction, stage):
        if stage != self.stage:  # one busy indicator per stage, named by it
            self.stop()
            self.indicator.start("%s: %s (%d %%)" % (self.label, stage, round(100 * fraction)), 0)
            self.running = True
            self.stage = stage
        self.indicator.next(True)  # raises when the user aborts an outermost indicator
        check = getattr(FreeCAD, "checkAbort", None)
        if check is not None:
            check()  # raises FreeCADAbort once the user pressed Esc and confirmed
        return True

    def stop(self):
        if self.running:
            self.indicator.stop()
            self.running = False
