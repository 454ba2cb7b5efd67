#!/usr/bin/env bash
# README command 2: install what is missing, build, run every test: the CLI cases on the Release
# build users run, and the whole suite under AddressSanitizer + UBSan.
#
# Two builds share the work so that the whole run stays well inside CI's limit on 2 cores (the
# project's own bound is 40 minutes):
#  1. build/ (plain Release): the library, the CLI, the benchmarks (compiled, not run) and the unit
#     tests labelled `sanitize_skip` (tests/CMakeLists.txt says why each one is); it runs the CLI
#     cases, the install test and those unit tests. Release is what users run, so the CLI's
#     behaviour (exit codes, messages, outputs) is checked on it.
#  2. build-asan/ (SIGMATAU_SANITIZE: -fsanitize=address,undefined, -O1, no debug info): the
#     library, the CLI and every unit test not labelled sanitize_skip; it runs every test not so
#     labelled (unit tests and CLI cases) under the sanitizers.
# The slow precision test and the address-space-limit cases run only in stage 1, the other unit
# tests only in stage 2. A fresh clone took 25.4 min on this 2-core VM on 2026-11-29 (plain
# build 4.7 min, its tests 1.4, sanitized build 10.6, sanitized tests 8.7; the slowest test,
# test_fit_guards, 196 s under the sanitizers), with a demo build beside it for its last 7 min.
# SIGMATAU_TEST_STAGES=plain or =asan runs one stage only.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs="$(nproc)"
stages="${SIGMATAU_TEST_STAGES:-plain asan}"
start=$SECONDS
elapsed() { echo "test.sh: $1 done at $((SECONDS - start)) s" >&2; }

scripts/install-deps.sh test

# Unit tests are the executables built from tests/test_*.cpp (CTest names them the same).
unit_tests=()
for f in tests/test_*.cpp; do unit_tests+=("$(basename "$f" .cpp)"); done
is_unit_test() { [[ " ${unit_tests[*]} " == *" $1 "* ]]; }
# The build targets of a build directory (Ninja's `help`), without CMake's utility targets.
build_targets() {
  cmake --build "$1" --target help | sed -n 's/^\([A-Za-z0-9_.+-]*\): phony$/\1/p' |
    grep -Ev '^(test|edit_cache|rebuild_cache|list_install_components|install|sigmatau_test_main)$|\.(a|so)$'
}

if [[ " $stages " == *" plain "* ]]; then
  cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
  # Every build target except the unit tests that run sanitized (the target list from Ninja's
  # `help`, minus CMake's own utility targets).
  skip=$(ctest --test-dir build -N -L sanitize_skip | sed -n 's/^ *Test *#[0-9]*: *//p')
  targets=()
  while IFS= read -r t; do
    if is_unit_test "$t" && [[ " $(echo $skip) " != *" $t "* ]]; then continue; fi
    targets+=("$t")
  done < <(build_targets build)
  cmake --build build -j "$jobs" --target "${targets[@]}"
  elapsed "plain build"
  # Everything that is not a unit test, then the unit tests kept out of the sanitized stage.
  # Tests labelled needs_unit_tests run a unit-test executable (not built here): stage 2 runs them.
  ctest --test-dir build --output-on-failure -j "$jobs" -E '^test_' -LE needs_unit_tests
  ctest --test-dir build --output-on-failure -j "$jobs" -R '^test_' -L sanitize_skip
  elapsed "plain tests"
fi

if [[ " $stages " == *" asan "* ]]; then
  # -O1: ASan's recommended level, and it compiles much faster than -O3 under instrumentation;
  # no -g (Release flags replaced): reports name functions, not lines (rebuild with -g to debug).
  # NDEBUG is not set, so SIGMATAU_ASSERT is checked too.
  cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS_RELEASE="-O1" \
    -DSIGMATAU_SANITIZE=ON -DSIGMATAU_BUILD_BENCH=OFF >/dev/null
  # Everything but the unit tests labelled sanitize_skip (the CLI and the tools its cases use too).
  asan_targets=()
  skip=$(ctest --test-dir build-asan -N -L sanitize_skip | sed -n 's/^ *Test *#[0-9]*: *//p')
  while IFS= read -r t; do
    if is_unit_test "$t" && [[ " $(echo $skip) " == *" $t "* ]]; then continue; fi
    asan_targets+=("$t")
  done < <(build_targets build-asan)
  cmake --build build-asan -j "$jobs" --target "${asan_targets[@]}"
  elapsed "sanitized build"
  # detect_leaks=0: LeakSanitizer needs ptrace, which CI containers often forbid; ASan's memory
  # errors and UBSan (halt on the first report) are what this stage is for.
  ASAN_OPTIONS=detect_leaks=0:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    ctest --test-dir build-asan --output-on-failure -j "$jobs" -LE sanitize_skip
  elapsed "sanitized tests"
fi
