#!/usr/bin/env bash
# Fetches held-out meshes for bench_scans: 22 models of CGAL's demo data (Debian's libcgal-demo, the source of
# ../shared/data) that no rule was tuned on, organic and CAD, closed and open, 1k to 26k vertices. Prints the
# comma-separated list bench_scans --models takes.
#
#   scripts/heldout_meshes.sh [DIR]    (default: build/heldout; needs apt's package lists, run apt-get update first)
#   build/release/bench/bench_scans --models "$(scripts/heldout_meshes.sh)" --conditions vertices --views 3
set -euo pipefail
dir=${1:-build/heldout}
models=(armadillo diplodocus man bear mannequin-devil ChineseDragon-10kv blade cheese lion-head bull dino homer femur
        cow triceratops elk head hand knot1 rotor_small couplingdown mushroom)
mkdir -p "$dir"
dir=$(cd "$dir" && pwd)
if [[ ! -f $dir/${models[-1]}.off ]]; then
  work=$(mktemp -d)
  trap 'rm -rf "$work"' EXIT
  (cd "$work" && apt-get download libcgal-demo >&2)
  dpkg-deb -x "$work"/libcgal-demo_*.deb "$work/deb"
  tar -xzf "$work/deb/usr/share/doc/libcgal-dev/data.tar.gz" -C "$work" data/meshes
  for m in "${models[@]}"; do cp "$work/data/meshes/$m.off" "$dir/"; done
fi
list=""
for m in "${models[@]}"; do list+="${list:+,}$dir/$m.off"; done
echo "$list"
