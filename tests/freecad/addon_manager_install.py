"""Installs a release zip with FreeCAD's own Addon Manager installer code
(Mod/AddonManager: addonmanager_installer.AddonInstaller, FreeCAD 1.0 and
later), headless, as a catalogue entry whose zip_url is the zip installs it:
downloaded from PLUNGE_AM_URL (bundle_suite.py serves it on 127.0.0.1) into
the profile's user Mod folder, under the name PlungeRough. Nothing is fixed up
after it: the layout, and the execute bits it drops, are what users get.

Run by freecadcmd (bundle_suite.py). Exits 0 with the installed folder on a
line "INSTALLED=<path>", 1 with one line saying why."""
import os
import sys
import traceback

import FreeCAD


def main():
    url = os.environ["PLUNGE_AM_URL"]
    folder = os.path.join(FreeCAD.getHomePath(), "Mod", "AddonManager")
    sys.path.insert(0, folder)
    import addonmanager_installer as installer_module
    from Addon import Addon

    mod = os.path.join(FreeCAD.getUserAppDataDir(), "Mod")
    os.makedirs(mod, exist_ok=True)
    # The allowed Python packages from the Addon Manager's own list: its
    # constructor would fetch them from GitHub (no network here).
    installer_module.AddonInstaller._load_local_allowed_packages_list()
    addon = Addon("PlungeRough", url, Addon.Status.NOT_INSTALLED, "")
    installer = installer_module.AddonInstaller(addon)
    installer.installation_path = mod
    errors = []
    installer.failure.connect(lambda _addon, message: errors.append(message))
    real = installer._install_by_zip

    def install_by_zip():  # 1.0's run() fails in its own handler: keep the cause
        try:
            return real()
        except Exception as e:
            errors.append("%s: %s" % (type(e).__name__, e))
            raise

    installer._install_by_zip = install_by_zip
    try:
        ok = installer.run()
    except Exception as e:
        ok = False
        errors.append("%s: %s" % (type(e).__name__, e))
    folder = os.path.join(mod, "PlungeRough")
    if not ok or not os.path.isfile(os.path.join(folder, "package.xml")):
        print("addon_manager_install: FreeCAD %s's installer did not install %s: %s" % (
            ".".join(FreeCAD.Version()[:3]), url, "; ".join(errors) or "no package.xml in %s" % folder), flush=True)
        return 1
    print("INSTALLED=%s" % folder, flush=True)
    return 0


try:
    code = main()
except Exception:
    traceback.print_exc()
    code = 1
sys.stdout.flush()
sys.exit(code)
