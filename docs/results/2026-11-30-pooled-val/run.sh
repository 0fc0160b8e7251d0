#!/bin/bash
# Check 70 (plan.md), from anywhere; resumable (a rendered sample or a report is kept).
set -euo pipefail
cd "$(dirname "$0")/../../.."  # the repository root
R=runs/c70
mkdir -p $R
export OMP_NUM_THREADS=1
V="--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml"
VARY="--config sim/presets/panel-vary.toml"
SV="--config sim/presets/side-view.toml"
for s in line:"$V $VARY" sw:"$V $VARY $SV"; do  # the second validation twin (seed 304)
  name=${s%%:*}; cfg=${s#*:}
  for k in 0 1; do
    # shellcheck disable=SC2086
    .venv/bin/station render --out data/$name-pv-val-304 $cfg --count 600 --seed 304 --defects 0.4 --validation \
      --shard $k/2 > $R/render-val-304-$name-$k.log 2>&1 &
  done
  wait
done
for s in line-panel:"$V" sw:"$V $SV"; do  # the fresh seed
  name=${s%%:*}; cfg=${s#*:}
  for k in 0 1; do
    # shellcheck disable=SC2086
    .venv/bin/station render --out data/$name-heldout-1172 $cfg --count 500 --seed 1172 --defects 0.5 --heldout \
      --shard $k/2 > $R/render-1172-$name-$k.log 2>&1 &
  done
  wait
done
E="--no-synthetic --no-plots"
[ -f $R/val-line-304/scores.csv ] || .venv/bin/station eval --model model/weights/default \
  --data data/line-pv-val-304 --split val $E --out $R/val-line-304 > $R/val-line-304.log 2>&1 &
[ -f $R/val-WS-304/scores.csv ] || .venv/bin/station eval --model runs/c68/WS --data data/sw-pv-val-304 \
  --split val --presence-rule row_contrast $E --out $R/val-WS-304 > $R/val-WS-304.log 2>&1 &
wait
[ -f $R/eval-line-1172/scores.csv ] || .venv/bin/station eval --model model/weights/default \
  --data data/line-panel-heldout-1172 --val-data data/line-pv-val $E --out $R/eval-line-1172 \
  > $R/eval-line-1172.log 2>&1 &
[ -f $R/eval-WS-1172/scores.csv ] || .venv/bin/station eval --model runs/c68/WS --data data/sw-heldout-1172 \
  --val-data data/sw-pv-val --presence-rule row_contrast $E --out $R/eval-WS-1172 > $R/eval-WS-1172.log 2>&1 &
wait
D=docs/results/2026-11-30-pooled-val
.venv/bin/python $D/combine70.py runs/c67/val-default,$R/val-line-304 runs/c69/val-WS,$R/val-WS-304 \
  $R/eval-line-1172 $R/eval-WS-1172 data/line-panel-heldout-1172 1172 > $D/combine70-1172.md
echo done > $R/done
