#!/bin/sh
# Every test: GoogleTest (C++ core), pytest under Debian's python3 (module and CLI).
set -eu
ROOT=$(cd "$(dirname "$0")/.." && pwd)
sh "$ROOT/resources/setup.sh"
cd "$ROOT/build"
ctest --output-on-failure -j"$(nproc)"
