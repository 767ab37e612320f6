#!/usr/bin/env bash
# Installs the CI build into a temporary prefix, then builds and runs tests/downstream/ against it twice: as a CMake
# package (find_package(pcsketch)) and through pkg-config; then configures pcsketch as a subproject. Run after
# scripts/test.sh (it installs the build that script tested).
set -euo pipefail
cd "$(dirname "$0")/.."
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
build="build/$(bash scripts/test-preset.sh)"
cmake --install "$build" --prefix "$tmp/prefix" > /dev/null
# The wrapped libraries stay inside: no installed header includes them, the exported targets do not name nanoflann
# (header-only, not needed by users), cairo and Embree are link-only.
if grep -rE '#include <(nanoflann|embree|cairo|png)' "$tmp/prefix/include"; then
  echo "downstream: an installed header includes a wrapped library" >&2
  exit 1
fi
config=$(dirname "$(find "$tmp/prefix" -name pcsketchConfig.cmake)")
if grep -q nanoflann "$config"/pcsketchTargets*.cmake; then
  echo "downstream: the installed package refers to nanoflann" >&2
  exit 1
fi
"$tmp/prefix/bin/pcsketch" --version > /dev/null

# The Python module, when the build has one, is installed too and imports from the prefix alone.
if compgen -G "$build/python/pcsketch*.so" > /dev/null; then
  module=$(find "$tmp/prefix" -name 'pcsketch*.so' -print -quit)
  if [ -z "$module" ]; then
    echo "downstream: the Python module was built but not installed" >&2
    exit 1
  fi
  PYTHONPATH=$(dirname "$module") /usr/bin/python3 -c \
    'import sys, pcsketch; assert pcsketch.__file__.startswith(sys.argv[1]), pcsketch.__file__' "$tmp/prefix"
fi

cmake -S tests/downstream -B "$tmp/cmake" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH="$tmp/prefix" \
  > /dev/null
cmake --build "$tmp/cmake" > /dev/null
"$tmp/cmake/downstream"

PKG_CONFIG_PATH=$(dirname "$(find "$tmp/prefix" -name pcsketch.pc)")
export PKG_CONFIG_PATH
if pkg-config --cflags pcsketch | grep -q -e cairo -e embree; then
  echo "downstream: pkg-config --cflags pcsketch names a wrapped library" >&2
  exit 1
fi
# shellcheck disable=SC2046  # pkg-config prints flags meant to be split
c++ -std=c++20 -O1 -o "$tmp/downstream_pc" tests/downstream/main.cpp $(pkg-config --cflags --libs pcsketch)
"$tmp/downstream_pc"

# As a subproject (add_subdirectory, FetchContent): the library and its alias, no tests, benches or Python module
# (configure only).
mkdir "$tmp/sub"
cat > "$tmp/sub/CMakeLists.txt" <<EOF
cmake_minimum_required(VERSION 3.25)
project(wrapper LANGUAGES CXX)
add_subdirectory($PWD pcsketch)
if(NOT TARGET pcsketch::pcsketch OR TARGET test_core OR TARGET bench_view OR TARGET pcsketch_python)
  message(FATAL_ERROR "pcsketch as a subproject: expected pcsketch::pcsketch alone")
endif()
EOF
cmake -S "$tmp/sub" -B "$tmp/sub/build" -G Ninja > /dev/null
echo "downstream: find_package(pcsketch) and pkg-config builds ran; the Python module imports from the prefix; as a subproject, the library alone"
