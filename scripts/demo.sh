#!/usr/bin/env bash
# README command 1: install what is missing, build, run the main job on the built-in demo:
# a 10 h log simulated from the shipped Safran STIM300 data sheet, analysed end to end into
# demo-output/ (report.html, results.json, summary.md, plots, filter files).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh
build/cli/sigmatau demo -o "${1:-demo-output}" --force
