#!/usr/bin/env bash
# README command 1: install what is missing, build, run the main job on the built-in demo.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh
out=${1:-demo-output}
# Until `sigmatau demo` exists (issue 7) the main job is `sigmatau adev` on a shipped example log.
build/cli/sigmatau adev examples/gyro_static_100Hz.csv.gz --time-column t --unit deg/s \
  --out-unit deg/h --format table
build/cli/sigmatau adev examples/gyro_static_100Hz.csv.gz --time-column t --unit deg/s \
  --format json -o "$out/adev.json" --force
echo "wrote $out/adev.json" >&2
