#!/bin/bash
# Check 65 (plan.md), from anywhere; resumable (a rendered sample, a fit or a report is kept).
set -euo pipefail
cd "$(dirname "$0")/../../.."  # the repository root
R=runs/c65
NS=docs/results/2026-11-30-report-1167/no-stray.toml
mkdir -p $R
export OMP_NUM_THREADS=1
V="--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml
   --config sim/presets/panel-vary.toml"
for half in 0 1; do  # the train split's shards only (k % 10 >= 3 of 20), as rule 62's render.sh
  (for j in 3 4 5 6 7 8 9; do
     .venv/bin/station render --out data/line-pf-train-C $V --config sim/presets/finish-vary.toml --config $NS \
       --count 900 --seed 101 --defects 0.4 --defects-in-train --shard $(( j + 10 * half ))/20
   done) > $R/render-train-$half.log 2>&1 &
done
wait
for k in 0 1; do
  .venv/bin/station render --out data/line-pv-val-B $V --config $NS --count 600 --seed 303 --defects 0.4 \
    --validation --shard $k/2 > $R/render-val-$k.log 2>&1 &
done
wait
[ -f $R/S2.json ] || .venv/bin/station variation --model runs/r52/F/default --refit --data data/line-pf-train-C \
  --val-data data/line-pf-val-B --decision variation --out $R/S2 > $R/S2.log 2>&1
if [ ! -f $R/SL.json ]; then
  .venv/bin/station residual --model $R/S2 --data data/line-pf-train-C --val-data data/line-pf-val-B --members 1 \
    --steps 3000 --second-look --out $R/SL-cal > $R/SL.log 2>&1
  .venv/bin/station threshold --model $R/SL-cal --data data/line-pv-val-B >> $R/SL.log 2>&1
  .venv/bin/python -c "import sys; from model.draem.checkpoint import copy_checkpoint; copy_checkpoint(*sys.argv[1:])" \
    $R/SL-cal $R/SL
fi
for set in B A; do
  d=data/line-panel-heldout-1167; [ $set = B ] && d=$d-B
  [ -f $R/eval-SL-$set/scores.csv ] || .venv/bin/station eval --model $R/SL --data $d --val-data data/line-pv-val-B \
    --no-synthetic --no-plots --out $R/eval-SL-$set > $R/eval-SL-$set.log 2>&1
done
echo done > $R/done
