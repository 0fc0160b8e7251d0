#!/bin/bash
# Check 66 (plan.md), from anywhere; resumable (a rendered sample, a fit or a report is kept).
set -euo pipefail
cd "$(dirname "$0")/../../.."  # the repository root
R=runs/c66
mkdir -p $R
export OMP_NUM_THREADS=1
V="--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml"
FV="--config sim/presets/front-view.toml"  # last: its exposure replaces the panel line's
VARY="--config sim/presets/panel-vary.toml"
FINISH="--config sim/presets/finish-vary.toml"
for half in 0 1; do  # the train split's shards only (k % 10 >= 3 of 20), as check 65
  (for j in 3 4 5 6 7 8 9; do
     .venv/bin/station render --out data/fv-train $V $VARY $FINISH $FV --count 900 --seed 101 --defects 0.4 \
       --defects-in-train --shard $(( j + 10 * half ))/20
   done) > $R/render-train-$half.log 2>&1 &
done
wait
for k in 0 1; do
  .venv/bin/station render --out data/fv-pf-val $V $VARY $FINISH $FV --count 600 --seed 303 --defects 0.4 \
    --validation --shard $k/2 > $R/render-pf-val-$k.log 2>&1 &
done
wait
for k in 0 1; do
  .venv/bin/station render --out data/fv-pv-val $V $VARY $FV --count 600 --seed 303 --defects 0.4 \
    --validation --shard $k/2 > $R/render-pv-val-$k.log 2>&1 &
done
wait
for k in 0 1; do
  .venv/bin/station render --out data/fv-heldout-1167 $V $FV --count 400 --seed 1167 --defects 0.6 --heldout \
    --shard $k/2 > $R/render-heldout-$k.log 2>&1 &
done
wait
[ -f $R/F2.json ] || .venv/bin/station variation --model runs/r52/F/default --refit --data data/fv-train \
  --val-data data/fv-pf-val --decision variation --out $R/F2 > $R/F2.log 2>&1
if [ ! -f $R/F.json ]; then
  .venv/bin/station residual --model $R/F2 --data data/fv-train --val-data data/fv-pf-val --members 1 \
    --steps 3000 --second-look --out $R/F-cal > $R/F.log 2>&1
  .venv/bin/station threshold --model $R/F-cal --data data/fv-pv-val >> $R/F.log 2>&1
  .venv/bin/python -c "import sys; from model.draem.checkpoint import copy_checkpoint; copy_checkpoint(*sys.argv[1:])" \
    $R/F-cal $R/F
fi
[ -f $R/eval-F/scores.csv ] || .venv/bin/station eval --model $R/F --data data/fv-heldout-1167 \
  --val-data data/fv-pv-val --no-synthetic --no-plots --out $R/eval-F > $R/eval-F.log 2>&1
for m in F:data/fv-pv-val default:data/line-pv-val; do  # each file's scores on its validation set's parts
  name=${m%%:*}; d=${m#*:}; model=$R/F; [ $name = default ] && model=model/weights/default
  [ -f $R/val-$name/scores.csv ] || .venv/bin/station eval --model $model --data $d --split val \
    --no-synthetic --no-plots --out $R/val-$name > $R/val-$name.log 2>&1
done
echo done > $R/done
