#!/bin/sh
# Installs the FreeCAD addon (Init.py, InitGui.py, package.xml, freecad_plugin/,
# icons, panels and the compiled planner beside them) into FreeCAD's user Mod
# folder, replacing an older copy. Needs a build (resources/setup.sh).
set -eu
ROOT=$(cd "$(dirname "$0")/.." && pwd)
MOD=$(cd /tmp && freecadcmd -c "import FreeCAD; print('MODDIR=' + FreeCAD.getUserAppDataDir() + 'Mod')" 2>/dev/null \
      | sed -n 's/^MODDIR=//p' | tr -d '\r')
if [ -z "$MOD" ]; then
  echo "install_addon: could not ask FreeCAD for its user Mod folder" >&2
  exit 1
fi
rm -rf "$MOD/PlungeRough"
cmake --install "$ROOT/build" --component freecad_addon --prefix "$MOD" >/dev/null
echo "installed the addon in $MOD/PlungeRough"
