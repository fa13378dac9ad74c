"""The Linux bundle as a user installs it (docs/install.md), then FreeCAD's
end-to-end cases on it (the tests marked "bundle": a pocket, a sculptured
floor and the 3D allowance through its mesh, rest plunging, a cancel, the
simulator and the posts).

The zip (PLUNGE_TEST_BUNDLE; tests/run.sh makes it with resources/bundle.sh)
is unzipped with Python's zipfile, as FreeCAD's Addon Manager unpacks, so the
program loses its execute bit, into the Mod folder of a fresh FreeCAD profile.
freecadcmd then runs the cases with that profile: the addon is the one FreeCAD
loaded from there, it plans through the bundle's program, and neither the
build tree nor a compiled module is on its path.

PLUNGE_BUNDLE_WINE=1 (the Windows bundle, tests/portable/run.sh): its program
runs under wine, named to the addon by PLUNGE_ROUGH_PLANNER, with a wine
prefix of its own.

Run by Debian's python3 (ctest "freecad_bundle"); PLUNGE_BUNDLE_HOME is the
profile's folder, made anew."""
import os
import shutil
import subprocess
import sys
import zipfile

HERE = os.path.dirname(os.path.abspath(__file__))
bundle = os.environ.get("PLUNGE_TEST_BUNDLE", "")
if not os.path.isfile(bundle):
    sys.exit("bundle_suite: PLUNGE_TEST_BUNDLE names no bundle (%r): sh resources/bundle.sh linux makes "
             "dist/PlungeRough-linux-x86_64.zip" % bundle)
home = os.environ["PLUNGE_BUNDLE_HOME"]
shutil.rmtree(home, ignore_errors=True)
os.makedirs(home)
env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PLUNGE_BUILD_DIR")}
env.update(XDG_DATA_HOME=os.path.join(home, "data"), XDG_CONFIG_HOME=os.path.join(home, "config"))


def freecad(script, *extra):
    path = os.path.join(home, "script.py")
    with open(path, "w") as f:
        f.write(script)
    return subprocess.run(["freecadcmd", path, *extra], cwd=home, env=env, capture_output=True, text=True,
                          timeout=3600)


said = freecad("import FreeCAD\nprint('MODDIR=' + FreeCAD.getUserAppDataDir() + 'Mod')\n")
mod = [l for l in said.stdout.replace("\r", "\n").splitlines() if l.startswith("MODDIR=")][0][len("MODDIR="):]
with zipfile.ZipFile(bundle) as z:
    z.extractall(mod)
addon = os.path.join(mod, "PlungeRough")
print("bundle_suite: %s unzipped into %s" % (os.path.basename(bundle), mod), flush=True)
env.update(PLUNGE_ADDON=addon, PLUNGE_SUITE="freecad_bundle")
if os.environ.get("PLUNGE_BUNDLE_WINE") == "1":
    env.update(WINEPREFIX=os.path.join(home, "wine"), WINEDEBUG="-all", WINEDLLOVERRIDES="mscoree,mshtml=",
               PLUNGE_ROUGH_PLANNER="wine '%s'" % os.path.join(addon, "bin", "plunge-rough.exe"))
run = subprocess.run(["freecadcmd", os.path.join(HERE, "run_suite.py")], cwd=home, env=env, timeout=3600)
sys.exit(run.returncode)
