#!/bin/bash
# Check 64d (plan-64d.md), from anywhere; resumable (a rendered sample, a fit or a report is kept).
set -euo pipefail
cd "$(dirname "$0")/../../.."  # the repository root
S=docs/results/2026-11-30-report-1167
R=runs/c64d
mkdir -p $R
export OMP_NUM_THREADS=1
P="--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml
   --config sim/presets/panel-vary.toml --config sim/presets/finish-vary.toml --config $S/no-stray.toml"
for half in 0 1; do  # the train split's shards only (k % 10 >= 3 of 20), as rule 62's render.sh
  (for j in 3 4 5 6 7 8 9; do
     .venv/bin/station render --out data/line-pf-train-B $P --count 540 --seed 101 --defects 0 \
       --shard $(( j + 10 * half ))/20
   done) > $R/render-train-$half.log 2>&1 &
done
wait
for k in 0 1; do
  .venv/bin/station render --out data/line-pf-val-B $P --count 600 --seed 303 --defects 0.4 --validation \
    --shard $k/2 > $R/render-val-$k.log 2>&1 &
done
wait
[ -f $R/S.json ] || .venv/bin/station variation --model runs/r52/F/default --refit --data data/line-pf-train-B \
  --val-data data/line-pf-val-B --decision variation --fit-parts 376 --out $R/S > $R/S.log 2>&1
[ -f $R/eval-S/scores.csv ] || .venv/bin/station eval --model $R/S --data data/line-panel-heldout-1167-B \
  --val-data data/line-pf-val-B --no-synthetic --no-plots --out $R/eval-S > $R/eval-S.log 2>&1
[ -f $R/eval-U/scores.csv ] || .venv/bin/station eval --model runs/r62/Fv --data data/line-panel-heldout-1167 \
  --val-data data/line-pf-val --no-synthetic --no-plots --out $R/eval-U > $R/eval-U.log 2>&1
.venv/bin/python $S/compare64d.py $R/eval-U $R/eval-S > $S/fitted-shielded-1167.md
