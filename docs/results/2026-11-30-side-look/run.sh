#!/bin/bash
# Check 69's fresh seed (plan.md), from anywhere; resumable. WS comes from look.sh.
set -euo pipefail
cd "$(dirname "$0")/../../.."  # the repository root
R=runs/c69
mkdir -p $R
export OMP_NUM_THREADS=1
V="--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml"
SV="--config sim/presets/side-view.toml"
for k in 0 1; do
  .venv/bin/station render --out data/line-panel-heldout-1171 $V --count 400 --seed 1171 --defects 0.6 --heldout \
    --shard $k/2 > $R/render-line-1171-$k.log 2>&1 &
done
wait
for k in 0 1; do
  .venv/bin/station render --out data/sw-heldout-1171 $V $SV --count 400 --seed 1171 --defects 0.6 --heldout \
    --shard $k/2 > $R/render-side-1171-$k.log 2>&1 &
done
wait
[ -f $R/val-WS/scores.csv ] || .venv/bin/station eval --model runs/c68/WS --data data/sw-pv-val --split val \
  --no-synthetic --no-plots --out $R/val-WS > $R/val-WS.log 2>&1
[ -f $R/eval-line-1171/scores.csv ] || .venv/bin/station eval --model model/weights/default \
  --data data/line-panel-heldout-1171 --val-data data/line-pv-val --no-synthetic --no-plots --out $R/eval-line-1171 \
  > $R/eval-line-1171.log 2>&1 &
[ -f $R/eval-WS-1171/scores.csv ] || .venv/bin/station eval --model runs/c68/WS --data data/sw-heldout-1171 \
  --val-data data/sw-pv-val --no-synthetic --no-plots --out $R/eval-WS-1171 > $R/eval-WS-1171.log 2>&1 &
wait
echo done > $R/done-1171
