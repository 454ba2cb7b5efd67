#!/usr/bin/env bash
# README command 2: install what is missing, build, run every test.
# SIGMATAU_SANITIZE_STAGE=1 adds the sanitizer stage: the whole suite again built with
# AddressSanitizer + UBSan (SIGMATAU_SANITIZE) in build-asan/, tests labelled `sanitize_skip`
# left out. It is opt-in for now: measured at ~9 + 7 min on top of the ~8-10 min plain run on
# 2 cores, it does not fit CI's 20-minute budget yet (issue 9).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh test
scripts/build.sh
ctest --test-dir build --output-on-failure -j "$(nproc)"

if [[ "${SIGMATAU_SANITIZE_STAGE:-0}" == 1 ]]; then
  # -O1: ASan's recommended level, and it compiles much faster than -O3 under instrumentation.
  cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS_RELEASE="-O1" \
    -DSIGMATAU_SANITIZE=ON -DSIGMATAU_BUILD_BENCH=OFF >/dev/null
  cmake --build build-asan -j "$(nproc)"
  # detect_leaks=0: LeakSanitizer needs ptrace, which CI containers often forbid; ASan's memory
  # errors and UBSan (halt on the first report) are what this stage is for.
  ASAN_OPTIONS=detect_leaks=0:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    ctest --test-dir build-asan --output-on-failure -j "$(nproc)" -LE sanitize_skip
fi
