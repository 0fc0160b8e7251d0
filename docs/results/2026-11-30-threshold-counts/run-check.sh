#!/bin/bash
# A two-camera check on a fresh seed: render the line and side twins, evaluate each camera's file, compare at a
# split's thresholds. Usage, from anywhere: run-check.sh SEED SPLIT_JSON (SPLIT_JSON relative to this folder).
# Resumable: a rendered sample, a report or a comparison already made is kept. Check 72: run-check.sh 1174 split-b1.json
set -euo pipefail
SEED=$1 SPLIT=$(cd "$(dirname "$0")" && pwd)/$2
cd "$(dirname "$0")/../../.."  # the repository root
R=runs/check-$SEED
mkdir -p $R
export OMP_NUM_THREADS=1
V="--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml"
for s in line-panel:"$V" sw:"$V --config sim/presets/side-view.toml"; do
  name=${s%%:*}; cfg=${s#*:}
  for k in 0 1; do
    # shellcheck disable=SC2086
    .venv/bin/station render --out data/$name-heldout-$SEED $cfg --count 500 --seed $SEED --defects 0.5 --heldout \
      --shard $k/2 > $R/render-$name-$k.log 2>&1 &
  done
  wait
done
E="--no-synthetic --no-plots"
[ -f $R/eval-line/scores.csv ] || .venv/bin/station eval --model model/weights/default \
  --data data/line-panel-heldout-$SEED --val-data data/line-pv-val $E --out $R/eval-line > $R/eval-line.log 2>&1 &
[ -f $R/eval-side/scores.csv ] || .venv/bin/station eval --model runs/make-side-model/side \
  --data data/sw-heldout-$SEED --val-data data/sw-pv-val --presence-rule row_contrast $E --out $R/eval-side \
  > $R/eval-side.log 2>&1 &
wait
.venv/bin/station compare $R/eval-line $R/eval-side --split "$SPLIT" --out $R/two-cameras
echo done > $R/done
