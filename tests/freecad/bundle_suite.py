"""A bundle as a user installs it (docs/install.md), then FreeCAD's
end-to-end cases on it (the tests marked "bundle": a pocket, a sculptured
floor and the 3D allowance through its mesh, rest plunging, a cancel, the
simulator and the posts).

The zip is PLUNGE_TEST_BUNDLE: a platform's own (tests/run.sh makes the Linux
one with resources/bundle.sh), or the universal one (PlungeRough-<version>.zip,
resources/bundle.sh all: every platform's program in bin/<os>-<arch>/, and a
package.xml beside its PlungeRough/ folder that leads FreeCAD to it).
- FreeCAD 1.0 and later install the universal zip with their own Addon
  Manager installer code (addon_manager_install.py), from a local URL served
  here, as a catalogue entry's zip_url is installed: it unpacks the zip into
  Mod/PlungeRough/ as it is, with Python's zipfile (execute bits lost).
- Otherwise (a platform's zip, or FreeCAD 0.20, whose Addon Manager has no
  installer to run headless) the zip is unzipped with Python's zipfile into
  the Mod folder, as a user unzips it there.
freecadcmd then runs the cases with that profile: the addon is the one FreeCAD
loaded from there, it plans through the bundle's program (the one for this
machine), and neither the build tree nor a compiled module is on its path.

PLUNGE_BUNDLE_WINE=1 (the Windows bundle, tests/portable/run.sh): its program
runs under wine, named to the addon by PLUNGE_ROUGH_PLANNER, with a wine
prefix of its own.

Run by Debian's python3 (ctest "freecad_bundle"); PLUNGE_BUNDLE_HOME is the
profile's folder, made anew."""
import functools
import http.server
import os
import shutil
import subprocess
import sys
import threading
import time
import zipfile

HERE = os.path.dirname(os.path.abspath(__file__))
bundle = os.environ.get("PLUNGE_TEST_BUNDLE", "")
# PLUNGE_TEST_BUNDLE_WAIT=SECONDS: the zip may still be on its way (CI's
# chroots start their tests while the host builds it; tests/fresh/run.sh
# copies it in when it is there, or writes BUNDLE.failed when the host gave up).
deadline = time.monotonic() + float(os.environ.get("PLUNGE_TEST_BUNDLE_WAIT", "0") or 0)
while bundle and not os.path.isfile(bundle) and not os.path.exists(bundle + ".failed") and time.monotonic() < deadline:
    time.sleep(5)
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


said = freecad("import FreeCAD, os\nprint('MODDIR=' + FreeCAD.getUserAppDataDir() + 'Mod')\n"
              "print('INSTALLER=%d' % os.path.isfile(os.path.join(FreeCAD.getHomePath(), 'Mod', 'AddonManager', "
              "'addonmanager_installer.py')))\n")
lines = said.stdout.replace("\r", "\n").splitlines()
mod = [l for l in lines if l.startswith("MODDIR=")][0][len("MODDIR="):]
has_installer = "INSTALLER=1" in lines
with zipfile.ZipFile(bundle) as z:
    universal = "package.xml" in z.namelist()
if universal and has_installer:
    # Served from here, downloaded by the Addon Manager's code in freecadcmd.
    handler = functools.partial(http.server.SimpleHTTPRequestHandler, directory=os.path.dirname(bundle))
    server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), handler)
    threading.Thread(target=server.serve_forever, daemon=True).start()
    env["PLUNGE_AM_URL"] = "http://127.0.0.1:%d/%s" % (server.server_address[1], os.path.basename(bundle))
    run = freecad(open(os.path.join(HERE, "addon_manager_install.py")).read())
    server.shutdown()
    installed = [l for l in run.stdout.replace("\r", "\n").splitlines() if l.startswith("INSTALLED=")]
    if run.returncode != 0 or not installed:
        sys.exit("bundle_suite: FreeCAD's Addon Manager did not install %s:\n%s%s" % (
            os.path.basename(bundle), run.stdout[-3000:], run.stderr[-3000:]))
    # The package.xml beside PlungeRough/ leads FreeCAD to the addon in it.
    addon = os.path.join(installed[0][len("INSTALLED="):], "PlungeRough")
    print("bundle_suite: %s installed by FreeCAD's Addon Manager into %s" % (os.path.basename(bundle), mod),
          flush=True)
else:
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
