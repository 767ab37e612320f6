#!/usr/bin/env bash
# Regenerates the gallery of docs/gallery/: a 512 px drawing of the bundled sample, of six shared models and of a
# noisy fandisk sample next to its clean twin, each with the paper's Fig. 19 stage images (b contours, c ridge-valley lines, d fused, e thickness, f shadow).
#
#   scripts/gallery.sh [PCSKETCH_BINARY]    (default: build/pcsketch)
#
# The shared models are read from ../shared/data (next to the repository); missing ones are skipped.
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${1:-build/pcsketch}
data=../shared/data
out=docs/gallery
size=512x512
mkdir -p "$out"

# name, input, view flags (the default view is the paper's: orthographic, looking along +z, y up).
draw() {
  local name=$1 input=$2
  shift 2
  if [[ ! -f $input ]]; then
    echo "gallery: skipping $name ($input not found)" >&2
    return
  fi
  echo "gallery: $name" >&2
  "$bin" -q draw "$input" --size "$size" "$@" -o "$out/$name.png" --stages "$out/$name"
}

draw sample data/bunny.ply --azimuth -35 --elevation 15
draw bunny "$data/bunny.off"
draw camel "$data/camel.off" --view 1,0.15,0.6
draw fandisk "$data/fandisk.off" --view 1,1,1
draw kitten "$data/kitten.xyz" --view 0,0,-1
draw building "$data/building.ply" --up 0,0,1 --view 1,0.7,-0.6
draw hippo "$data/hippo1.ply"  # a sparse scan from one side: its border is the outline

# A scan's noise next to its clean twin: 200k samples of the fandisk, clean and with σ = 0.2% of the diagonal.
if [[ -f $data/fandisk.off ]]; then
  samples=$(mktemp -d)
  trap 'rm -rf "$samples"' EXIT
  "$bin" -q sample "$data/fandisk.off" -n 200000 -o "$samples/clean.ply"
  "$bin" -q sample "$data/fandisk.off" -n 200000 --noise 0.002 -o "$samples/noisy.ply"
  draw fandisk_clean "$samples/clean.ply" --view 1,1,1
  draw fandisk_noisy "$samples/noisy.ply" --view 1,1,1
fi

# A sheet of technical drawing (third angle, one scale for front, top and side, scale bar) and a pen-plotter file.
if [[ -f $data/fandisk.off ]]; then
  echo "gallery: fandisk sheet" >&2
  "$bin" -q draw "$data/fandisk.off" --size 400x400 --sheet third --scale-bar --no-hatching -o "$out/fandisk_sheet.png" \
    -o "$out/fandisk_sheet.svg"
fi
echo "gallery: sample plotter" >&2
"$bin" -q draw data/bunny.ply --azimuth -35 --elevation 15 --size "$size" --plotter --page-width-mm 200 \
  -o "$out/sample_plotter.svg" -o "$out/sample_plotter.png"
