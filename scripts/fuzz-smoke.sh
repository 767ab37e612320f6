#!/usr/bin/env bash
# Fuzz smoke run: builds the libFuzzer targets with the "fuzz" preset (clang) and runs each for FUZZ_SECONDS
# (default 24: five targets, two minutes in all) seconds, seeded with tests/fixtures. The four readers take the bytes
# as a file; fuzz_cli takes them as a command line (flags and values) run in-process on tiny built-in clouds.
# Exits non-zero if any target finds a crash, a sanitizer report, a leak, or a single allocation over 64 MB (inputs
# are at most 4 KB, so that would be a size taken on trust).
# FUZZ_BUILD_DIR overrides the build directory (default build/fuzz, from the preset).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${FUZZ_SECONDS:-24}"
build="${FUZZ_BUILD_DIR:-build/fuzz}"
targets=(fuzz_read_ply fuzz_read_las fuzz_read_xyz fuzz_read_other fuzz_cli)

cmake --preset fuzz -B "$build"
cmake --build "$build" --target "${targets[@]}" -j2

# Leaks in system libraries that are not ours (fontconfig's configuration, loaded when cairo lays out a label).
export LSAN_OPTIONS="suppressions=$PWD/.ci/lsan.supp${LSAN_OPTIONS:+:$LSAN_OPTIONS}"
corpus="$(mktemp -d)"
trap 'rm -rf "$corpus"' EXIT
mkdir -p "$build/artifacts"
artifacts="$(cd "$build/artifacts" && pwd)"  # absolute: fuzz_cli runs the CLI in its own directory
for target in "${targets[@]}"; do
  mkdir -p "$corpus/$target"
  echo "== $target: ${seconds}s"
  # New inputs go to the temporary first directory; the fixtures are read-only seeds.
  if ! "$build/fuzz/$target" "$corpus/$target" tests/fixtures/ok tests/fixtures/malformed \
      -max_total_time="$seconds" -max_len=4096 -malloc_limit_mb=64 -rss_limit_mb=1024 -timeout=5 \
      -print_final_stats=1 -artifact_prefix="$artifacts/$target-" >"$corpus/$target.log" 2>&1; then
    tail -n 40 "$corpus/$target.log" >&2
    echo "fuzz-smoke: $target failed; reproducer in $build/artifacts/" >&2
    exit 1
  fi
  grep -E "^stat::(number_of_executed_units|new_units_added|peak_rss_mb)" "$corpus/$target.log"
done
echo "fuzz-smoke: all targets ran ${seconds}s without findings"
