#!/usr/bin/env bash
# Builds with warnings as errors and runs the whole GoogleTest suite through ctest. Under CI (CI set), the release
# preset already builds with warnings as errors (see CMakePresets.json), so the build setup.sh made is tested as it is
# instead of compiling everything a second time; elsewhere the ci preset builds into build/ci.
set -euo pipefail
cd "$(dirname "$0")/.."
preset=$(bash scripts/test-preset.sh)
cmake --preset "$preset"
cmake --build --preset "$preset"
ctest --preset "$preset"
