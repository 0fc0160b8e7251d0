#!/bin/bash
# Check 68's fresh seed (plan-1170.md), from anywhere; resumable.
set -euo pipefail
cd "$(dirname "$0")/../../.."  # the repository root
R=runs/c68
mkdir -p $R
export OMP_NUM_THREADS=1
V="--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml"
SV="--config sim/presets/side-view.toml"
for k in 0 1; do
  .venv/bin/station render --out data/line-panel-heldout-1170 $V --count 400 --seed 1170 --defects 0.6 --heldout \
    --shard $k/2 > $R/render-line-1170-$k.log 2>&1 &
done
wait
for k in 0 1; do
  .venv/bin/station render --out data/sw-heldout-1170 $V $SV --count 400 --seed 1170 --defects 0.6 --heldout \
    --shard $k/2 > $R/render-side-1170-$k.log 2>&1 &
done
wait
[ -f $R/eval-line-1170/scores.csv ] || .venv/bin/station eval --model model/weights/default \
  --data data/line-panel-heldout-1170 --val-data data/line-pv-val --no-synthetic --no-plots --out $R/eval-line-1170 \
  > $R/eval-line-1170.log 2>&1 &
[ -f $R/eval-W-1170/scores.csv ] || .venv/bin/station eval --model $R/W --data data/sw-heldout-1170 \
  --val-data data/sw-pv-val --no-synthetic --no-plots --out $R/eval-W-1170 > $R/eval-W-1170.log 2>&1 &
wait
D=docs/results/2026-11-30-wide-dome
.venv/bin/python $D/combine68.py runs/c67/val-default $R/val-W $R/eval-line-1170 $R/eval-W-1170 \
  data/line-panel-heldout-1170 1170 > $D/combine68-1170.md
echo done > $R/done-1170
