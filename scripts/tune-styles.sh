#!/usr/bin/env bash
# Re-derives the style controller sets from the default set: each is the default tuned towards
# another normative group and other timing targets (fuzzygait tune is deterministic for a seed).
# Takes a few minutes per style on two cores; not part of the build or the tests.
#   scripts/tune-styles.sh [BUILD_DIR]     (default: build)
set -euo pipefail
cd "$(dirname "$0")/.."
fuzzygait=${1:-build}/fuzzygait
common=(--controllers controllers/default --generations 250 --polish 50 --recovery 2 --sigma 0.1)

"$fuzzygait" tune "${common[@]}" --seed 21 -o controllers/energetic --name energetic \
  --description "Light and brisk: quick steps and a quick swing." \
  --reference schwartz2008_fast --cycle 0.86 0.94 --stance 55 58 --knee-peak 64 70 \
  --pelvis-range 50 70

"$fuzzygait" tune "${common[@]}" --seed 22 -o controllers/heavy --name heavy \
  --description "Heavy and deliberate: slower limbs with more inertia, a lower knee, a flatter path of the pelvis." \
  --reference schwartz2008_slow --cycle 1.18 1.30 --stance 63 66 --knee-peak 54 58 \
  --pelvis-range 20 34 --minimum-inertia 0.05

"$fuzzygait" tune "${common[@]}" --seed 23 -o controllers/cautious --name cautious \
  --description "Tired or cautious: slow steps, long double support, little knee lift." \
  --reference schwartz2008_veryslow --cycle 1.35 1.55 --stance 65 70 --knee-peak 48 54 \
  --pelvis-range 15 30
