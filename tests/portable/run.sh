#!/bin/sh
# The Windows bundle, tested where this Debian machine can run it (CI's native
# run, .ci/run): resources/bundle.sh windows, Debian's wine, then
# 1. tests/python/test_portable.py with PLUNGE_TEST_PORTABLE=1: both bundles'
#    programs fully static, the Windows program's plans those of the Linux
#    program on the golden inputs, paths with any character, a kill;
# 2. FreeCAD's end-to-end cases (tests/freecad/bundle_suite.py) on the Windows
#    bundle unzipped into a fresh profile, planning through its program under
#    wine (PLUNGE_ROUGH_PLANNER): FreeCAD 0.20 on Debian 12.
# Needs the README's build (tests/run.sh) and the Linux bundle (dist/).
set -eu
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
. "$ROOT/resources/apt.sh"
sh "$ROOT/resources/bundle.sh" windows
install_missing wine wine64 procps
cd "$ROOT/build"
PLUNGE_TEST_PORTABLE=1 /usr/bin/python3 -m pytest -q -p no:cacheprovider "$ROOT/tests/python/test_portable.py" \
  --build-dir "$ROOT/build"
PLUNGE_TEST_BUNDLE=$ROOT/dist/PlungeRough-windows-x86_64.zip PLUNGE_BUNDLE_WINE=1 \
  PLUNGE_BUNDLE_HOME=$ROOT/build/freecad-home/freecad_bundle_wine /usr/bin/python3 "$ROOT/tests/freecad/bundle_suite.py"
