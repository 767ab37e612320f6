#!/usr/bin/env bash
# Installs the CI build into a temporary prefix, then builds and runs tests/downstream/ against it twice: as a CMake
# package (find_package(pcsketch)) and through pkg-config. Run after scripts/test.sh (it installs build/ci).
set -euo pipefail
cd "$(dirname "$0")/.."
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cmake --install build/ci --prefix "$tmp/prefix" > /dev/null
# nanoflann is header-only and must not be required of users; cairo and Embree are link-only.
if grep -q nanoflann "$tmp"/prefix/lib/cmake/pcsketch/*.cmake; then
  echo "downstream: the installed package refers to nanoflann" >&2
  exit 1
fi
test -x "$tmp/prefix/bin/pcsketch"

cmake -S tests/downstream -B "$tmp/cmake" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH="$tmp/prefix" \
  > /dev/null
cmake --build "$tmp/cmake" > /dev/null
"$tmp/cmake/downstream"

export PKG_CONFIG_PATH="$tmp/prefix/lib/pkgconfig"
if pkg-config --cflags pcsketch | grep -q -e cairo -e embree; then
  echo "downstream: pkg-config --cflags pcsketch names a wrapped library" >&2
  exit 1
fi
# shellcheck disable=SC2046  # pkg-config prints flags meant to be split
c++ -std=c++20 -O1 -o "$tmp/downstream_pc" tests/downstream/main.cpp $(pkg-config --cflags --libs pcsketch)
"$tmp/downstream_pc"
echo "downstream: find_package(pcsketch) and pkg-config builds ran"
