#!/bin/bash
# Held-out types on the second report set (seed 1167), from anywhere; resumable. The look network trained without
# each type (../2026-11-29-finish-vary/heldout/nets.sh, which also scores it on seed 1165), thresholded on the line
# as built, scored on seed 1167 as built with the thresholds held fixed.
set -euo pipefail
cd "$(dirname "$0")/../../.."  # the repository root
export OMP_NUM_THREADS=1
H=runs/h63
for t in stain chip missing_stud dent scratch; do
  [ -f $H/H-$t.json ] || docs/results/2026-11-29-finish-vary/heldout/nets.sh $t  # a lost runs/ dir: train it again
  [ -f $H/eval-1167-H-$t/scores.csv ] || .venv/bin/station eval --model $H/H-$t --data data/line-panel-heldout-1167 \
    --val-data data/line-pv-val --no-synthetic --no-plots --out $H/eval-1167-H-$t > $H/eval-1167-H-$t.log 2>&1
done
