#!/bin/sh
# Sanitizers and fuzzing (CI runs this after the README's test command):
# 1. the C++ tests and the fuzz inputs (seed corpus + regressions) built with
#    clang, AddressSanitizer and UndefinedBehaviorSanitizer (build-sanitize/);
# 2. libFuzzer on the JSON-to-plan path for FUZZ_SECONDS (default 240), under
#    the same sanitizers: a crash, a sanitizer report, an exception other than
#    plunge::Error, a gouge, a run past 900 s (the sanitizers and the coverage
#    instrumentation make runs about 17 times slower: about a minute without
#    them) or past 4 GB fails. What it finds is written to
#    build-sanitize/fuzz-findings/: add it to tests/fuzz/regressions/.
#    FUZZ_SEED (default 1) fixes libFuzzer's mutations, so that a run that
#    fails in CI fails again here; FUZZ_SEED=0 takes a random seed (longer,
#    exploring runs: FUZZ_SEED=0 FUZZ_SECONDS=3600).
set -eu
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
# The project's packages (setup.sh) and Debian's clang with its sanitizer and
# libFuzzer runtimes.
sh "$ROOT/resources/setup.sh" --packages-only
. "$ROOT/resources/apt.sh"
install_missing clang libclang-rt-dev
B="$ROOT/build-sanitize"
cmake -S "$ROOT" -B "$B" -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DPLUNGE_SANITIZE=ON -DPLUNGE_FUZZ=ON -DPLUNGE_BUILD_PYTHON=OFF -DPLUNGE_WERROR="${PLUNGE_WERROR:-OFF}" >/dev/null
cmake --build "$B" -j"$(nproc)"
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
(cd "$B" && ctest --output-on-failure -j"$(nproc)")
corpus="$B/fuzz-corpus"
findings="$B/fuzz-findings"
mkdir -p "$corpus" "$findings"
"$B/tests/fuzz_plan" -max_total_time="${FUZZ_SECONDS:-240}" -timeout=900 -rss_limit_mb=4096 -seed="${FUZZ_SEED:-1}" \
  -dict="$ROOT/tests/fuzz/plan.dict" -artifact_prefix="$findings/" -print_final_stats=1 \
  "$corpus" "$ROOT/tests/fuzz/corpus" "$ROOT/tests/fuzz/regressions"
