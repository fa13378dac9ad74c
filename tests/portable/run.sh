#!/bin/sh
# The bundles, tested where this Debian machine can run them (CI's native
# run, .ci/run): resources/bundle.sh all (Linux x86-64 and aarch64, Windows,
# macOS arm64 and x86-64, the universal zip and SHA256SUMS), Debian's wine and
# qemu-user-static, then
# 1. tests/python/test_portable.py with PLUNGE_TEST_PORTABLE=1: the Linux
#    programs fully static, the Windows one Windows' own DLLs only, the macOS
#    ones macOS's own libraries only, for their CPU, the arm64 one signed
#    (resources/macho_check.py); the Windows program's plans under wine and
#    the aarch64 program's under qemu those of the x86-64 Linux program on
#    the golden inputs; Windows paths with any character, a kill; the
#    universal zip's programs and SHA256SUMS;
# 2. FreeCAD's end-to-end cases (tests/freecad/bundle_suite.py) on the Windows
#    bundle unzipped into a fresh profile, planning through its program under
#    wine (PLUNGE_ROUGH_PLANNER): FreeCAD 0.20 on Debian 12.
# Needs the README's build (tests/run.sh); the Linux bundle is made again
# from build-bundle/ (nothing left to build when .ci/run's bundle-linux ran).
set -eu
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
. "$ROOT/resources/apt.sh"
sh "$ROOT/resources/bundle.sh" all
install_missing wine wine64 procps qemu-user-static
cd "$ROOT/build"
PLUNGE_TEST_PORTABLE=1 /usr/bin/python3 -m pytest -q -p no:cacheprovider "$ROOT/tests/python/test_portable.py" \
  --build-dir "$ROOT/build"
PLUNGE_TEST_BUNDLE=$ROOT/dist/PlungeRough-windows-x86_64.zip PLUNGE_BUNDLE_WINE=1 \
  PLUNGE_BUNDLE_HOME=$ROOT/build/freecad-home/freecad_bundle_wine /usr/bin/python3 "$ROOT/tests/freecad/bundle_suite.py"
