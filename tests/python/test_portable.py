"""The bundles' programs (resources/bundle.sh): fully static, and the same
plans as the planner built here, on Linux, on Windows under wine and on
64-bit ARM Linux under qemu; the macOS programs, which nothing here runs,
checked statically (resources/macho_check.py); the universal zip and
SHA256SUMS.

The bundles are dist/PlungeRough-{linux-x86_64,windows-x86_64,linux-aarch64,
macos-arm64,macos-x86_64}.zip and dist/PlungeRough-VERSION.zip
(`sh resources/bundle.sh all` makes them all). Where one is missing, or wine
or qemu-aarch64-static is, its cases are skipped, unless
PLUNGE_TEST_PORTABLE=1 (CI's run, tests/portable/run.sh), which asks for all
of them; PLUNGE_TEST_PORTABLE=0 (CI's native test command, beside that run)
skips them all: the portable stage runs them once.

Golden inputs: every test shape and floor kind of test_program.py, and the
FreeCAD demo's floor as the addon meshes it (demo_mesh_input.py)."""
import concurrent.futures
import hashlib
import json
import os
import re
import shutil
import struct
import subprocess
import sys
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
pytestmark = pytest.mark.skipif(os.environ.get("PLUNGE_TEST_PORTABLE") == "0",
                                reason="PLUNGE_TEST_PORTABLE=0: tests/portable/run.sh runs these")
QEMU = shutil.which("qemu-aarch64-static")
sys.path.insert(0, os.path.join(ROOT, "resources"))
import macho_check  # noqa: E402

# The universal zip's folders, bin/OS-ARCH/, and each one's platform zip.
PLATFORMS = {"linux-x86_64": "plunge-rough", "linux-aarch64": "plunge-rough", "windows-x86_64": "plunge-rough.exe",
             "macos-arm64": "plunge-rough", "macos-x86_64": "plunge-rough"}


def need(what, present):
    if not present:
        if REQUIRED:
            pytest.fail("PLUNGE_TEST_PORTABLE=1 and %s is missing" % what)
        pytest.skip("%s is missing (sh resources/bundle.sh all)" % what)


def unzipped(name, tmp_path_factory):
    path = os.path.join(DIST, "PlungeRough-%s.zip" % name)
    need(path, os.path.isfile(path))
    out = tmp_path_factory.mktemp(name)
    with zipfile.ZipFile(path) as z:
        names = z.namelist()
        z.extractall(out)
    return out, names


@pytest.fixture(scope="module")
def linux(tmp_path_factory):
    out, names = unzipped("linux-x86_64", tmp_path_factory)
    program = out / "PlungeRough" / "bin" / "plunge-rough"
    program.chmod(0o755)  # zipfile drops it, as the Addon Manager's unzip does
    return program, names


@pytest.fixture(scope="module")
def windows(tmp_path_factory):
    out, names = unzipped("windows-x86_64", tmp_path_factory)
    need("wine", WINE)
    return out / "PlungeRough" / "bin" / "plunge-rough.exe", names


@pytest.fixture(scope="module")
def aarch64(tmp_path_factory):
    out, names = unzipped("linux-aarch64", tmp_path_factory)
    program = out / "PlungeRough" / "bin" / "plunge-rough"
    program.chmod(0o755)
    return program, names


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
    assert build_info(program).startswith("PlungeRough's planner for Linux on x86-64 (linux-x86_64): ")
    run = subprocess.run([str(program), "call"], input='{"call": "about"}', capture_output=True, text=True, env={})
    about = json.loads(run.stdout)
    assert about["system"] == "linux" and "brep" not in about["floors"] and "mesh" in about["floors"]


def test_the_windows_bundle_imports_only_windows_own_dlls(windows):
    program, names = windows
    check_bundle(names, "plunge-rough.exe")
    assert build_info(program).startswith("PlungeRough's planner for Windows on x86-64 (windows-x86_64): ")
    dump = subprocess.run(["x86_64-w64-mingw32-objdump", "-p", str(program)], capture_output=True, text=True).stdout
    dlls = {line.split("DLL Name:")[1].strip().lower() for line in dump.splitlines() if "DLL Name:" in line}
    assert dlls and dlls <= {"kernel32.dll", "msvcrt.dll", "shell32.dll", "user32.dll", "advapi32.dll"}, dlls


def build_info(program):
    return (program.parent / "build-info.txt").read_text()


def test_the_linux_program_plans_as_the_build_here(linux, cli, demo_mesh):
    program, _ = linux
    for name, data in inputs(demo_mesh).items():
        ours = plan_with([cli], data)
        assert without_timings(plan_with([str(program)], data)) == without_timings(ours), name


def differences(a, b, where="plan", tolerance=1e-9, absolute=False):
    """Where two plans differ: in kind, length, text or key, or in a number by
    more than `tolerance` (mm; or, unless `absolute`, its fraction of numbers
    above 1)."""
    if isinstance(a, float) or isinstance(b, float):
        allowed = tolerance if absolute else tolerance * max(1, abs(a))
        ok = isinstance(a, (int, float)) and isinstance(b, (int, float)) and abs(a - b) <= allowed
        return [] if ok else ["%s: %r != %r" % (where, a, b)]
    if isinstance(a, dict) and isinstance(b, dict):
        if set(a) != set(b):
            return ["%s: keys %s" % (where, sorted(set(a) ^ set(b)))]
        return [d for k in a for d in differences(a[k], b[k], "%s.%s" % (where, k), tolerance, absolute)]
    if isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            return ["%s: %d != %d items" % (where, len(a), len(b))]
        return [d for k, (x, y) in enumerate(zip(a, b))
                for d in differences(x, y, "%s[%d]" % (where, k), tolerance, absolute)]
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


def test_the_aarch64_bundle_holds_a_fully_static_aarch64_program(aarch64):
    program, names = aarch64
    check_bundle(names, "plunge-rough")
    header = subprocess.run(["readelf", "-h", str(program)], capture_output=True, text=True).stdout
    headers = subprocess.run(["readelf", "-lW", str(program)], capture_output=True, text=True).stdout
    dynamic = subprocess.run(["readelf", "-d", str(program)], capture_output=True, text=True).stdout
    assert re.search(r"Class:\s+ELF64", header) and re.search(r"Machine:\s+AArch64", header), header
    assert "INTERP" not in headers and "NEEDED" not in dynamic
    assert build_info(program).startswith("PlungeRough's planner for Linux on 64-bit ARM, aarch64 (linux-aarch64): ")
    need("qemu-aarch64-static", QEMU)
    run = subprocess.run([QEMU, str(program), "call"], input='{"call": "about"}', capture_output=True, text=True,
                         env={})
    about = json.loads(run.stdout)
    assert about["system"] == "linux" and "brep" not in about["floors"] and "mesh" in about["floors"]


def test_the_aarch64_program_plans_as_the_linux_program(linux, aarch64, demo_mesh):
    """Under qemu: the same plunges, order, tools, statistics, summary and
    pictures, every number within 1e-6 (mm) of the x86-64 program's. Both
    are built with -ffp-contract=off, so the ARM one fuses no multiply-adds;
    what remains is glibc's math functions on aarch64 (seen: about 1e-15
    relative on the expression and mesh floors, bit for bit elsewhere)."""
    need("qemu-aarch64-static", QEMU)
    data = inputs(demo_mesh)

    def both(name):
        return (plan_with([str(linux[0])], data[name]), plan_with([QEMU, str(aarch64[0])], data[name]))

    with concurrent.futures.ThreadPoolExecutor(max_workers=os.cpu_count() or 1) as pool:
        plans = dict(zip(data, pool.map(both, data)))
    for name, (on_x86, on_arm) in plans.items():
        assert on_x86["plunges"], name
        found = differences(without_timings(on_arm), without_timings(on_x86), tolerance=1e-6, absolute=True)
        assert not found, (name, found[:10])


@pytest.mark.parametrize("arch", ["arm64", "x86_64"])
def test_the_macos_bundle_passes_the_static_checks(arch, tmp_path_factory):
    """Nothing here runs a Mach-O program: its CPU, its libraries (macOS's
    own only) and, on Apple silicon, its code signature."""
    out, names = unzipped("macos-" + arch, tmp_path_factory)
    check_bundle(names, "plunge-rough")
    program = out / "PlungeRough" / "bin" / "plunge-rough"
    problems, info = macho_check.check(str(program), arch)
    assert not problems, problems
    assert [name for _, name in info["dylibs"]] == ["/usr/lib/libSystem.B.dylib"], info["dylibs"]
    about = {"arm64": "macOS on Apple silicon, arm64", "x86_64": "macOS on Intel, x86-64"}[arch]
    assert build_info(program).startswith("PlungeRough's planner for %s (macos-%s): " % (about, arch))
    with zipfile.ZipFile(os.path.join(DIST, "PlungeRough-macos-%s.zip" % arch)) as z:
        assert z.getinfo("PlungeRough/bin/plunge-rough").external_attr >> 16 & 0o111  # unzip keeps it runnable
    # The other Mac's CPU is said as such.
    other = {"arm64": "x86_64", "x86_64": "arm64"}[arch]
    assert any("CPU type" in p for p in macho_check.check(str(program), other)[0])


def mach_o(cputype, dylibs, signed):
    """A minimal 64-bit Mach-O executable's header and load commands."""
    commands = [struct.pack("<IIQQ", 0x80000028, 24, 0, 0)]  # LC_MAIN
    for name in dylibs:
        text = name.encode() + b"\0"
        size = (24 + len(text) + 7) // 8 * 8
        commands.append(struct.pack("<IIIIII", 0xC, size, 24, 2, 0x10000, 0x10000) + text.ljust(size - 24, b"\0"))
    body = b"".join(commands)
    if signed:
        offset = 32 + len(body) + 16
        body += struct.pack("<IIII", 0x1D, 16, offset, 12)
        tail = struct.pack(">III", 0xFADE0CC0, 12, 0)
    else:
        tail = b""
    ncmds = len(commands) + (1 if signed else 0)
    return struct.pack("<IiiIIIII", 0xFEEDFACF, cputype, 0, 2, ncmds, len(body), 0, 0) + body + tail


@pytest.mark.parametrize("arch,cputype,dylibs,signed,problem", [
    ("arm64", 0x0100000C, ["/usr/lib/libSystem.B.dylib"], True, None),
    ("x86_64", 0x01000007, ["/usr/lib/libSystem.B.dylib", "/usr/lib/libc++.1.dylib"], False, None),
    ("arm64", 0x0100000C, ["/usr/lib/libSystem.B.dylib"], False, "no code signature"),
    ("arm64", 0x0100000C, ["/usr/lib/libSystem.B.dylib", "/opt/homebrew/lib/libgmp.10.dylib"], True,
     "LC_LOAD_DYLIB /opt/homebrew/lib/libgmp.10.dylib: not one of macOS's own libraries"),
    ("x86_64", 0x0100000C, ["/usr/lib/libSystem.B.dylib"], True, "CPU type 0x0100000C, not x86_64's 0x01000007"),
    ("arm64", 0x0100000C, ["@rpath/libplunge.dylib"], True, "@rpath/libplunge.dylib: not one of"),
])
def test_the_mach_o_checks(tmp_path, arch, cputype, dylibs, signed, problem):
    """resources/macho_check.py on small made-up programs: what passes, and
    each check that fails said."""
    path = tmp_path / "program"
    path.write_bytes(mach_o(cputype, dylibs, signed))
    problems, _ = macho_check.check(str(path), arch)
    if problem is None:
        assert not problems, problems
    else:
        assert len(problems) == 1 and problem in problems[0], problems
    run = subprocess.run([sys.executable, os.path.join(ROOT, "resources", "macho_check.py"), str(path), arch],
                         capture_output=True, text=True)
    assert run.returncode == (0 if problem is None else 1), run.stderr
    elf = tmp_path / "elf"
    elf.write_bytes(b"\x7fELF" + bytes(60))
    assert "not a 64-bit Mach-O file" in macho_check.check(str(elf), arch)[0][0]


def version():
    with open(os.path.join(ROOT, "package.xml")) as f:
        return re.search(r"<version>([^<]+)</version>", f.read()).group(1)


def test_the_universal_zip_holds_every_program():
    """dist/PlungeRough-VERSION.zip: one folder PlungeRough/, the addon once,
    each platform's program and build-info.txt in bin/OS-ARCH/, byte for byte
    its platform zip's; nothing directly in bin/; beside the folder, the
    addon's package.xml leading FreeCAD into it (what the Addon Manager's
    unpacking into Mod/PlungeRough/ needs: bundle_suite.py installs it so)."""
    path = os.path.join(DIST, "PlungeRough-%s.zip" % version())
    need(path, os.path.isfile(path))
    with zipfile.ZipFile(path) as z:
        names = z.namelist()
        check_bundle([n for n in names if n != "package.xml"], "linux-x86_64/plunge-rough")
        in_bin = [n[len("PlungeRough/bin/"):] for n in names if n.startswith("PlungeRough/bin/")]
        assert sorted({n.split("/")[0] for n in in_bin}) == sorted(PLATFORMS) and all("/" in n for n in in_bin), in_bin
        for name, program in PLATFORMS.items():
            platform_zip = os.path.join(DIST, "PlungeRough-%s.zip" % name)
            need(platform_zip, os.path.isfile(platform_zip))
            with zipfile.ZipFile(platform_zip) as p:
                for f in (program, "build-info.txt"):
                    ours = z.getinfo("PlungeRough/bin/%s/%s" % (name, f))
                    assert z.read(ours) == p.read("PlungeRough/bin/" + f), (name, f)
                    assert ours.external_attr == p.getinfo("PlungeRough/bin/" + f).external_attr, (name, f)
                addon = sorted(n for n in p.namelist() if not n.startswith("PlungeRough/bin/"))
                assert addon == sorted(n for n in names if not n.startswith("PlungeRough/bin/")
                                       and n != "package.xml"), name
            assert ("(%s): %s" % (name, program)) in z.read("PlungeRough/bin/%s/build-info.txt" % name).decode()
        assert [n for n in names if not n.startswith("PlungeRough/")] == ["package.xml"]
        outer, inner = z.read("package.xml").decode(), z.read("PlungeRough/package.xml").decode()
        assert "<subdirectory>./PlungeRough</subdirectory>" in outer and "<subdirectory>./</subdirectory>" in inner
        icon = re.search(r"<icon>([^<]+)</icon>", outer).group(1)
        assert icon.startswith("PlungeRough/") and icon in names
        assert re.sub(r"<subdirectory>[^<]*</subdirectory>|<icon>[^<]*</icon>", "", outer) == \
            re.sub(r"<subdirectory>[^<]*</subdirectory>|<icon>[^<]*</icon>", "", inner)


def test_sha256sums_lists_every_zip():
    path = os.path.join(DIST, "SHA256SUMS")
    need(path, os.path.isfile(path))
    listed = {}
    with open(path) as f:
        for line in f:
            digest, name = line.rstrip("\n").split("  ", 1)  # sha256sum's format: sha256sum -c reads it
            listed[name] = digest
    expected = ["PlungeRough-%s.zip" % n for n in PLATFORMS] + ["PlungeRough-%s.zip" % version()]
    assert sorted(listed) == sorted(expected), listed
    for name, digest in listed.items():
        with open(os.path.join(DIST, name), "rb") as f:
            assert hashlib.sha256(f.read()).hexdigest() == digest, name
