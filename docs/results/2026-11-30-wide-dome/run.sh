#!/bin/bash
# Check 68 (plan.md), from anywhere; resumable (a rendered sample, a fit or a report is kept).
set -euo pipefail
cd "$(dirname "$0")/../../.."  # the repository root
R=runs/c68
mkdir -p $R
export OMP_NUM_THREADS=1
V="--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml"
SV="--config sim/presets/side-view.toml"  # last: the second camera and its flat dome (0.36 m wide)
VARY="--config sim/presets/panel-vary.toml"
FINISH="--config sim/presets/finish-vary.toml"
for half in 0 1; do  # the train split's shards only (k % 10 >= 3 of 20), as check 67
  (for j in 3 4 5 6 7 8 9; do
     .venv/bin/station render --out data/sw-train $V $VARY $FINISH $SV --count 900 --seed 101 --defects 0.4 \
       --defects-in-train --shard $(( j + 10 * half ))/20
   done) > $R/render-train-$half.log 2>&1 &
done
wait
for k in 0 1; do
  .venv/bin/station render --out data/sw-pv-val $V $VARY $SV --count 600 --seed 303 --defects 0.4 \
    --validation --shard $k/2 > $R/render-pv-val-$k.log 2>&1 &
done
wait
for k in 0 1; do
  .venv/bin/station render --out data/sw-heldout-1169 $V $SV --count 400 --seed 1169 --defects 0.6 --heldout \
    --shard $k/2 > $R/render-heldout-$k.log 2>&1 &
done
wait
for m in O:sv W:sw; do
  name=${m%%:*}; p=${m#*:}
  [ -f $R/$name.json ] || .venv/bin/station variation --model runs/r52/F/default --refit --data data/$p-train \
    --val-data data/$p-pv-val --decision variation --out $R/$name > $R/$name.log 2>&1
  [ -f $R/eval-$name/scores.csv ] || .venv/bin/station eval --model $R/$name --data data/$p-heldout-1169 \
    --val-data data/$p-pv-val --no-synthetic --no-plots --out $R/eval-$name > $R/eval-$name.log 2>&1
  [ -f $R/val-$name/scores.csv ] || .venv/bin/station eval --model $R/$name --data data/$p-pv-val --split val \
    --no-synthetic --no-plots --out $R/val-$name > $R/val-$name.log 2>&1
done
D=docs/results/2026-11-30-wide-dome
for name in O W; do
  .venv/bin/python docs/results/2026-11-30-front-view/compare66.py runs/c67/eval-line-1169 \
    data/line-panel-heldout-1169 $R/eval-$name runs/c67/val-default $R/val-$name 1169 > $D/compare-$name.md
done
.venv/bin/python $D/compare68.py runs/c67/eval-line-1169 data/line-panel-heldout-1169 $R/eval-O $R/eval-W \
  runs/c67/val-default $R/val-O $R/val-W > $D/compare68.md
echo done > $R/done
