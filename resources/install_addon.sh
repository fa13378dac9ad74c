#!/bin/sh
# Installs the FreeCAD addon (Init.py, InitGui.py, package.xml, freecad_plugin/,
# icons, panels, the planner program in bin/ and the module beside them) into FreeCAD's user Mod
# folder, replacing an older copy, then the plunge-mill tool bits (Tools/ in
# the addon; on FreeCAD 1.1 also the user's CAM asset library). Needs a build
# (resources/setup.sh), or --build: the packages, then only what the addon
# needs built (the one command for a clone made by FreeCAD's Addon Manager).
set -eu
ROOT=$(cd "$(dirname "$0")/.." && pwd)
if [ "${1:-}" = --build ]; then
  sh "$ROOT/resources/setup.sh" --packages-only
  cmake -S "$ROOT" -B "$ROOT/build" -DCMAKE_BUILD_TYPE=Release -DPython_EXECUTABLE=/usr/bin/python3 >/dev/null
  cmake --build "$ROOT/build" -j"$(nproc)" --target plunge_python plunge-rough
fi
MOD=$(cd /tmp && freecadcmd -c "import FreeCAD; print('MODDIR=' + FreeCAD.getUserAppDataDir() + 'Mod')" 2>/dev/null \
      | sed -n 's/^MODDIR=//p' | tr -d '\r')
if [ -z "$MOD" ]; then
  echo "install_addon: could not ask FreeCAD for its user Mod folder" >&2
  exit 1
fi
if [ "$(realpath -m "$MOD")" = "$(realpath "$ROOT/..")" ]; then
  # A clone made by FreeCAD's Addon Manager is the addon folder itself: keep
  # it, and put only what the build adds (the planner program in bin/, the
  # module and its library) beside its sources.
  ADDON=$ROOT
  staged=$(mktemp -d)
  cmake --install "$ROOT/build" --component freecad_addon --prefix "$staged" >/dev/null
  cp -P "$staged"/PlungeRough/*.so* "$ADDON/"
  mkdir -p "$ADDON/bin"
  cp "$staged"/PlungeRough/bin/* "$ADDON/bin/"
  rm -rf "$staged"
else
  ADDON=$MOD/PlungeRough
  rm -rf "$ADDON"
  cmake --install "$ROOT/build" --component freecad_addon --prefix "$MOD" >/dev/null
fi
tools=$(cd /tmp && PLUNGE_ADDON="$ADDON" freecadcmd "$ROOT/resources/install_tools.py" 2>&1 | tr -d '\r')
case $tools in *TOOLS=*) ;; *)
  printf '%s\n' "$tools" | tail -n 5 >&2
  echo "install_addon: could not make the plunge-mill tool bits" >&2
  exit 1;;
esac
echo "installed the addon in $ADDON, plunge-mill bits in $(printf '%s\n' "$tools" | sed -n 's/^.*TOOLS=//p')"
