#!/usr/bin/env bash
# Installs the Debian packages hullcheck needs (library, tests, benchmark peers) when missing.
# Usage: scripts/install-deps.sh   (as root, or with sudo available)
# ccache: a compiler cache outside the clone, used by scripts/test.sh, fuzz.sh and ompl2.sh.
set -euo pipefail
packages=(cmake g++ make clang-format pkg-config ccache
  libompl-dev libeigen3-dev liburdfdom-dev libassimp-dev libqhull-dev libyaml-cpp-dev
  libtinyxml2-dev libhwy-dev libcli11-dev libgtest-dev libgmock-dev libbenchmark-dev
  libfcl-dev libccd-dev libbullet-dev liborocos-kdl-dev libkdl-parser-dev
  ompl-demos libjs-three clang libclang-rt-dev
  pybind11-dev python3-dev python3-numpy python3-pytest)
# ompl-demos: ompl_benchmark_statistics, to check the benchmark logs; libjs-three: three.js,
# inlined into the HTML viewer that plan/validate write; clang + libclang-rt-dev: libFuzzer and
# the sanitizer runtimes for the fuzz targets (scripts/fuzz.sh); pybind11-dev, python3-dev,
# python3-numpy, python3-pytest: the Python package and its tests.
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  echo "installing: ${missing[*]}" >&2
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends \
    "${missing[@]}" >/dev/null
fi
