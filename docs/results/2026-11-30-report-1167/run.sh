#!/bin/bash
# Check 64 (plan.md), from anywhere; resumable (a rendered sample or a finished report is kept).
# Renders seed 1167 as the report set 1165 was rendered, then scores the shipped file on it.
set -euo pipefail
cd "$(dirname "$0")/../../.."  # the repository root
S=docs/results/2026-11-30-report-1167
R=runs/c64
mkdir -p $R
export OMP_NUM_THREADS=1
V="--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml"
SHARDS=${SHARDS:-0 1}  # which of the two shards this call renders (both by default, one per core)
for k in $SHARDS; do
  .venv/bin/station render $V --count 400 --seed 1167 --defects 0.6 --heldout --visibility \
    --out data/line-panel-heldout-1167 --shard $k/2 > $R/render-$k.log 2>&1 &
done
wait
[ -f $R/eval/eval.md ] || .venv/bin/station eval --model model/weights/default --data data/line-panel-heldout-1167 \
  --val-data data/line-pv-val --out $R/eval > $R/eval.log 2>&1
.venv/bin/python docs/results/2026-11-29-by-size/by_face.py $R/eval data/line-panel-heldout-1167 > $S/by-face-1167.md
