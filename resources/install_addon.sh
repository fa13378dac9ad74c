#!/bin/sh
# Installs the FreeCAD addon (Init.py, InitGui.py, package.xml, freecad_plugin/,
# icons, panels and the compiled planner beside them) into FreeCAD's user Mod
# folder, replacing an older copy, then the plunge-mill tool bits (Tools/ in
# the addon; on FreeCAD 1.1 also the user's CAM asset library). Needs a build
# (resources/setup.sh).
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
tools=$(cd /tmp && PLUNGE_ADDON="$MOD/PlungeRough" freecadcmd "$ROOT/resources/install_tools.py" 2>&1 | tr -d '\r')
case $tools in *TOOLS=*) ;; *)
  printf '%s\n' "$tools" | tail -n 5 >&2
  echo "install_addon: could not make the plunge-mill tool bits" >&2
  exit 1;;
esac
echo "installed the addon in $MOD/PlungeRough, plunge-mill bits in $(printf '%s\n' "$tools" | sed -n 's/^.*TOOLS=//p')"
