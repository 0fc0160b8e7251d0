#!/bin/bash
# Check 67 (plan.md), from anywhere; resumable (a rendered sample, a fit or a report is kept).
set -euo pipefail
cd "$(dirname "$0")/../../.."  # the repository root
R=runs/c67
mkdir -p $R
export OMP_NUM_THREADS=1
V="--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml"
SV="--config sim/presets/side-view.toml"  # last: the second camera and its flat dome
VARY="--config sim/presets/panel-vary.toml"
FINISH="--config sim/presets/finish-vary.toml"
for half in 0 1; do  # the train split's shards only (k % 10 >= 3 of 20), as checks 65-66
  (for j in 3 4 5 6 7 8 9; do
     .venv/bin/station render --out data/sv-train $V $VARY $FINISH $SV --count 900 --seed 101 --defects 0.4 \
       --defects-in-train --shard $(( j + 10 * half ))/20
   done) > $R/render-train-$half.log 2>&1 &
done
wait
for k in 0 1; do
  .venv/bin/station render --out data/sv-pf-val $V $VARY $FINISH $SV --count 600 --seed 303 --defects 0.4 \
    --validation --shard $k/2 > $R/render-pf-val-$k.log 2>&1 &
done
wait
for k in 0 1; do
  .venv/bin/station render --out data/sv-pv-val $V $VARY $SV --count 600 --seed 303 --defects 0.4 \
    --validation --shard $k/2 > $R/render-pv-val-$k.log 2>&1 &
done
wait
for k in 0 1; do
  .venv/bin/station render --out data/sv-heldout-1167 $V $SV --count 400 --seed 1167 --defects 0.6 --heldout \
    --shard $k/2 > $R/render-heldout-$k.log 2>&1 &
done
wait
[ -f $R/S2.json ] || .venv/bin/station variation --model runs/r52/F/default --refit --data data/sv-train \
  --val-data data/sv-pf-val --decision variation --out $R/S2 > $R/S2.log 2>&1
if [ ! -f $R/S.json ]; then
  .venv/bin/station residual --model $R/S2 --data data/sv-train --val-data data/sv-pf-val --members 1 \
    --steps 3000 --second-look --out $R/S-cal > $R/S.log 2>&1
  .venv/bin/station threshold --model $R/S-cal --data data/sv-pv-val >> $R/S.log 2>&1
  .venv/bin/python -c "import sys; from model.draem.checkpoint import copy_checkpoint; copy_checkpoint(*sys.argv[1:])" \
    $R/S-cal $R/S
fi
[ -f $R/eval-S/scores.csv ] || .venv/bin/station eval --model $R/S --data data/sv-heldout-1167 \
  --val-data data/sv-pv-val --no-synthetic --no-plots --out $R/eval-S > $R/eval-S.log 2>&1
for m in S:data/sv-pv-val default:data/line-pv-val; do  # each file's scores on its validation set's parts
  name=${m%%:*}; d=${m#*:}; model=$R/S; [ $name = default ] && model=model/weights/default
  [ -f $R/val-$name/scores.csv ] || .venv/bin/station eval --model $model --data $d --split val \
    --no-synthetic --no-plots --out $R/val-$name > $R/val-$name.log 2>&1
done
.venv/bin/python docs/results/2026-11-30-front-view/compare66.py docs/results/2026-11-30-report-1167/eval-1167 \
  data/line-panel-heldout-1167 $R/eval-S $R/val-default $R/val-S > docs/results/2026-11-30-side-view/compare67.md
echo done > $R/done
