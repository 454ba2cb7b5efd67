#!/usr/bin/env bash
# Installs, with apt, the Debian 12 packages sigmatau needs to build and plot; skips what is
# already there. With the argument "test" it adds what the test suite needs besides (Chromium,
# to render the HTML report). Run as root (or with sudo available).
set -euo pipefail
packages=(
  g++ cmake ninja-build pkg-config            # toolchain
  libeigen3-dev                               # linear algebra (fits, calibration)
  libfftw3-dev                                # Welch PSD
  libcli11-dev                                # command-line parsing
  doctest-dev                                 # unit tests
  libboost-dev                                # Boost.Math: chi-squared quantiles, special functions
  libyaml-cpp-dev                             # data-sheet files, filter YAML exports
  nlohmann-json3-dev                          # machine-readable results
  zlib1g-dev                                  # gzip-compressed logs
  libbz2-dev liblz4-dev libzstd-dev           # ROS bag chunk compression (bz2, lz4, zstd)
  libsqlite3-dev                              # rosbag2 .db3 storage
  libbenchmark-dev                            # bench/
  gnuplot-nox                                 # plots
)
if [[ "${1:-}" == "test" ]]; then
  packages+=(chromium)                        # the report is checked in a real browser
fi
if [[ "${1:-}" == "fuzz" ]]; then
  packages+=(clang libclang-rt-14-dev)        # libFuzzer harnesses (scripts/fuzz.sh)
fi
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "installing: ${missing[*]}" >&2
  sudo_cmd=()
  [[ $(id -u) -eq 0 ]] || sudo_cmd=(sudo)
  "${sudo_cmd[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
