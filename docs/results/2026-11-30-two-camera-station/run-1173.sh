#!/bin/bash
# Check 71 (plan-1173.md), from anywhere; resumable (a rendered sample or a report is kept).
set -euo pipefail
cd "$(dirname "$0")/../../.."  # the repository root
R=runs/c71
mkdir -p $R
export OMP_NUM_THREADS=1
V="--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml"
SV="--config sim/presets/side-view.toml"
for s in line-panel:"$V" sw:"$V $SV"; do
  name=${s%%:*}; cfg=${s#*:}
  for k in 0 1; do
    # shellcheck disable=SC2086
    .venv/bin/station render --out data/$name-heldout-1173 $cfg --count 500 --seed 1173 --defects 0.5 --heldout \
      --shard $k/2 > $R/render-1173-$name-$k.log 2>&1 &
  done
  wait
done
E="--no-synthetic --no-plots"
[ -f $R/eval-line-1173/scores.csv ] || .venv/bin/station eval --model model/weights/default \
  --data data/line-panel-heldout-1173 --val-data data/line-pv-val $E --out $R/eval-line-1173 \
  > $R/eval-line-1173.log 2>&1 &
[ -f $R/eval-side-1173/scores.csv ] || .venv/bin/station eval --model runs/make-side-model/side \
  --data data/sw-heldout-1173 --val-data data/sw-pv-val --presence-rule row_contrast $E --out $R/eval-side-1173 \
  > $R/eval-side-1173.log 2>&1 &
wait
D=docs/results/2026-11-30-two-camera-station
.venv/bin/station compare $R/eval-line-1173 $R/eval-side-1173 --split $D/split.json --out $R/two-cameras-1173
cp $R/two-cameras-1173/two-cameras.md $D/two-cameras-1173.md
echo done > $R/done
