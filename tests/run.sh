#!/bin/sh
# Every test: GoogleTest (C++ core), pytest under Debian's python3 (module and
# CLI), FreeCAD headless and in its GUI, and the Linux bundle installed into
# FreeCAD as a user installs it (freecad_bundle).
set -eu
ROOT=$(cd "$(dirname "$0")/.." && pwd)
sh "$ROOT/resources/setup.sh"
# The bundle under test: PLUNGE_TEST_BUNDLE when given (CI builds it once, on
# Debian 12, and tests that one everywhere), else this checkout's.
if [ -z "${PLUNGE_TEST_BUNDLE:-}" ]; then
  sh "$ROOT/resources/bundle.sh" linux
  PLUNGE_TEST_BUNDLE=$ROOT/dist/PlungeRough-linux-x86_64.zip
fi
export PLUNGE_TEST_BUNDLE
cd "$ROOT/build"
ctest --output-on-failure -j"$(nproc)"
