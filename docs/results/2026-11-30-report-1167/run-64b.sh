#!/bin/bash
# Check 64b (plan-64b.md), from anywhere; resumable. Seed 1168's 200 good parts three ways, then the shipped file's
# scores on each. SHARDS="0" or "1" renders one shard per call (default both, one per core).
set -euo pipefail
cd "$(dirname "$0")/../../.."  # the repository root
S=docs/results/2026-11-30-report-1167
R=runs/c64b
mkdir -p $R
export OMP_NUM_THREADS=1
V="--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml"
declare -A EXTRA=([A]="" [B]="--config $S/no-stray.toml" [C]="--config $S/fixed-exposure.toml")
for set in A B C; do
  for k in ${SHARDS:-0 1}; do
    .venv/bin/station render $V ${EXTRA[$set]} --count 200 --seed 1168 --defects 0 --heldout \
      --out data/twins-1168-$set --shard $k/2 > $R/render-$set-$k.log 2>&1 &
  done
  wait
done
.venv/bin/python $S/score64b.py data/twins-1168-A data/twins-1168-B data/twins-1168-C > $S/twins-1168.md
