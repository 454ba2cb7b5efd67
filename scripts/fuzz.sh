#!/usr/bin/env bash
# Builds the libFuzzer harnesses (clang, ASan + UBSan) into build-fuzz/ and runs each for
# FUZZ_SECONDS (default 60) from a seed corpus made of the test data. Crashes land in
# build-fuzz/crashes/<harness>/; turn each into a file under tests/data/bad/ or a regression test.
# Usage: scripts/fuzz.sh [harness...]   (default: all five)
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh fuzz
build=${FUZZ_BUILD_DIR:-build-fuzz}
seconds=${FUZZ_SECONDS:-60}
harnesses=("$@")
((${#harnesses[@]})) || harnesses=(fuzz_text_log fuzz_binary_log fuzz_units fuzz_spec fuzz_bag)
CXX=clang++ cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DSIGMATAU_FUZZ=ON \
  -DSIGMATAU_SANITIZE=ON -DSIGMATAU_BUILD_TESTS=OFF -DSIGMATAU_BUILD_BENCH=OFF >/dev/null
cmake --build "$build" -j "$(nproc)" --target "${harnesses[@]}" make_bag_seeds

# Seed corpora: the readers' harnesses take option bytes first (see fuzz/*.cpp).
seed() {  # seed DIR PREFIX_BYTES FILES...
  local dir=$1 prefix=$2
  shift 2
  mkdir -p "$dir"
  for f in "$@"; do
    [[ -f $f ]] || continue
    { printf "$prefix"; head -c 4096 "$f"; } >"$dir/$(basename "$f").$(printf "$prefix" | od -An -tx1 | tr -d ' \n')"
  done
}
corpus=$build/corpus
rm -rf "$corpus"
for p in '\x00' '\x01' '\x09' '\x11' '\x59' '\x41'; do
  seed "$corpus/fuzz_text_log" "$p" tests/data/logs/* tests/data/bad/*.csv tests/data/bad/*.txt tests/data/bad/*.tsv
done
for p in '\x00\x08' '\x03\x02' '\x06\x11' '\x02\x00'; do
  seed "$corpus/fuzz_binary_log" "$p" tests/data/bad/*.f32 tests/data/bad/*.f64 tests/data/bad/*.i16
done
mkdir -p "$corpus/fuzz_units"
i=0
for u in "deg/s" "°/√h" "mdps/rt-Hz" "ug/sqrt(Hz)" "m/s^2" "%/°C" "LSB/(°/s)" "0.1 deg/h" "rad/s^1.5" "1e-3 g"; do
  printf '%s' "$u" >"$corpus/fuzz_units/seed$((i++))"
done
seed "$corpus/fuzz_spec" '' specs/*.yaml tests/data/specs/*.yaml tests/data/fuzz/spec/*
# Earlier findings (tests/data/fuzz/<harness>/) already carry their option bytes.
cp tests/data/fuzz/text_log/* "$corpus/fuzz_text_log/" 2>/dev/null || true
"$build/fuzz/make_bag_seeds" "$corpus/fuzz_bag"  # whole small bags (a 4 kB head is no bag)
cp tests/data/fuzz/bag/* "$corpus/fuzz_bag/" 2>/dev/null || true

status=0
for h in "${harnesses[@]}"; do
  mkdir -p "$build/crashes/$h" "$corpus/$h"
  echo "== $h: ${seconds} s" >&2
  if ! "$build/fuzz/$h" "$corpus/$h" -max_total_time="$seconds" -max_len=65536 -rss_limit_mb=2048 \
      -timeout=10 -artifact_prefix="$build/crashes/$h/" -print_final_stats=1 \
      >"$build/$h.log" 2>&1; then
    status=1
    echo "   CRASH: see $build/$h.log and $build/crashes/$h/" >&2
  fi
  grep -E "stat::number_of_executed_units|stat::peak_rss_mb" "$build/$h.log" | sed 's/^/   /' >&2 || true
done
exit $status
