#!/usr/bin/env bash
# Fits the styles' terrain words: each style starts from the default set's words and files and
# is tuned on stairs up and down and on ramps up and down (fuzzygait tune-terrain, deterministic
# for a seed). The default set's words were written by hand and tuned the same way, starting
# from hand-written files; this script re-derives the styles' from them. About 10 minutes a
# style on two cores; not part of the build or the tests.
#   scripts/tune-terrain.sh [BUILD_DIR] [STYLE...]      (default: build; energetic heavy cautious)
set -euo pipefail
cd "$(dirname "$0")/.."
fuzzygait=${1:-build}/fuzzygait
shift || true
styles=("${@:-energetic heavy cautious}")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
for style in ${styles[@]}; do
  echo "== $style"
  "$fuzzygait" tune-terrain --style "$style" --words-from controllers/default --preset stairs-up \
    --words stairs:up --generations 120 --sigma 0.15 --seed 31 -o "$work/$style-1"
  "$fuzzygait" tune-terrain --controllers "$work/$style-1" --preset stairs-down \
    --words stairs:down --generations 120 --sigma 0.15 --seed 32 -o "$work/$style-2"
  "$fuzzygait" tune-terrain --controllers "$work/$style-2" --preset ramps-up \
    --words slopes:up --generations 100 --sigma 0.15 --seed 33 -o "$work/$style-3"
  "$fuzzygait" tune-terrain --controllers "$work/$style-3" --preset ramps-down \
    --words slopes:down --generations 100 --sigma 0.15 --seed 34 -o "$work/$style-4"
  rm -f controllers/"$style"/*.fll controllers/"$style"/manifest.json
  cp "$work/$style-4"/* controllers/"$style"/
done
