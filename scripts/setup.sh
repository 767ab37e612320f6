#!/usr/bin/env bash
# Installs every dependency (toolchain included) from Debian's packages, builds pcsketch in Release and draws the
# bundled sample cloud. Run as root on Debian 12 (or with sudo available).
set -euo pipefail
cd "$(dirname "$0")/.."
SUDO=""; [ "$(id -u)" -eq 0 ] || SUDO="sudo"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -q
$SUDO apt-get install -y -q --no-install-recommends \
  build-essential g++ cmake ninja-build pkg-config git ca-certificates \
  libeigen3-dev libnanoflann-dev libtbb-dev libcli11-dev libcairo2-dev libpng-dev libembree-dev nlohmann-json3-dev \
  libgtest-dev libgmock-dev libbenchmark-dev pybind11-dev python3-dev python3-numpy python3-pytest \
  clang libclang-rt-14-dev libxml2-utils
cmake --preset release
cmake --build --preset release
mkdir -p out
./build/release/pcsketch draw data/bunny.ply --azimuth -35 --elevation 15 \
  -o out/bunny.svg -o out/bunny.png -o out/bunny.pdf --json out/bunny.json
echo "setup: drew the bundled sample into out/bunny.{svg,png,pdf,json}"
