#!/bin/sh
# Installs what PlungeRough needs from Debian 12, 13 or testing (only what is missing) and builds it.
# Idempotent: run it as often as you like; both README commands start with it.
# --packages-only: install, do not build (tests/fuzz/run.sh builds its own).
set -eu
ROOT=$(cd "$(dirname "$0")/.." && pwd)

PACKAGES="cmake g++ make pkg-config
  libpolyclipping-dev libboost-dev libcgal-dev nlohmann-json3-dev libcli11-dev
  libeigen3-dev libmuparser-dev libtbb-dev
  libocct-foundation-dev libocct-modeling-data-dev libocct-modeling-algorithms-dev
  libocct-visualization-dev
  pybind11-dev python3-dev libgtest-dev libgmock-dev python3-pytest python3-shapely python3-jsonschema python3-scipy
  python3-numpy freecad xvfb xauth libgl1-mesa-dri"

. "$ROOT/resources/apt.sh"
install_missing $PACKAGES
# FreeCAD on Qt 6 (1.1, Debian forky) draws check marks and icons from SVG:
# Qt 6's SVG image plugin is only recommended by its GUI library, and
# --no-install-recommends leaves it out (every check box then looks unticked).
if installed libqt6gui6; then install_missing qt6-svg-plugins; fi
[ "${1:-}" = --packages-only ] && exit 0

cmake -S "$ROOT" -B "$ROOT/build" -DCMAKE_BUILD_TYPE=Release -DPython_EXECUTABLE=/usr/bin/python3 \
  -DPLUNGE_WERROR="${PLUNGE_WERROR:-OFF}" >/dev/null
cmake --build "$ROOT/build" -j"$(nproc)"
