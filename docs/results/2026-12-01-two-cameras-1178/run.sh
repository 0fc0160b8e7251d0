#!/bin/bash
# The two-camera station on seed 1178 (check 74's held-out set), a fourth fresh seed for rule 64's split
# (docs/second-camera.md): the side camera's twins of data/line-panel-heldout-1178 (rendered as it was: 400 parts,
# defects 0.6, --heldout --visibility), each camera's file evaluated, compared at split-b1.json's thresholds as checks
# 72-73 read seeds 1174, 1175 and 1177. A report, no decision. Resumable.
set -euo pipefail
cd "$(dirname "$0")/../../.."  # the repository root
SEED=1178
R=runs/check-$SEED
mkdir -p $R
export OMP_NUM_THREADS=1
V="--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml"
for k in 0 1; do
  # shellcheck disable=SC2086
  nice -n 10 .venv/bin/station render --out data/sw-heldout-$SEED $V --config sim/presets/side-view.toml --count 400 \
    --seed $SEED --defects 0.6 --heldout --visibility --shard $k/2 > $R/render-sw-$k.log 2>&1 &
done
wait
E="--no-synthetic --no-plots"
[ -f $R/eval-line/scores.csv ] || .venv/bin/station eval --model model/weights/default \
  --data data/line-panel-heldout-$SEED --val-data data/line-pv-val $E --out $R/eval-line > $R/eval-line.log 2>&1
[ -f $R/eval-side/scores.csv ] || .venv/bin/station eval --model runs/make-side-model/side \
  --data data/sw-heldout-$SEED --val-data data/sw-pv-val --presence-rule row_contrast $E --out $R/eval-side \
  > $R/eval-side.log 2>&1
.venv/bin/station compare $R/eval-line $R/eval-side --split docs/results/2026-11-30-threshold-counts/split-b1.json \
  --out $R/two-cameras
echo done > $R/done
