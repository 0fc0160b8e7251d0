#!/bin/bash
# The two-camera station on the new kinds (seed 1179), as the two-camera reports read seeds 1174-1178
# (docs/second-camera.md): the side camera's twins of data/new-kinds-1179 (rendered as it was: 400 parts, defects
# 0.6, blisters and debris only, --heldout --visibility), the side camera's file evaluated, the pair compared at rule
# 64's split (split-b1.json). Written before the twins were rendered; a report, no decision. Resumable.
set -euo pipefail
cd "$(dirname "$0")/../../.."  # the repository root
D=docs/results/2026-12-01-new-kinds
R=runs/c76
mkdir -p $R
export OMP_NUM_THREADS=1
V="--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml"
for k in 0 1; do
  # shellcheck disable=SC2086
  .venv/bin/station render --out data/sw-new-kinds-1179 $V --config sim/presets/side-view.toml --config $D/types.toml \
    --count 400 --seed 1179 --defects 0.6 --heldout --visibility --shard $k/2 > $R/render-sw-$k.log 2>&1 &
done
wait
[ -f $R/eval-side-new-kinds/scores.csv ] || .venv/bin/station eval --model runs/make-side-model/side \
  --data data/sw-new-kinds-1179 --val-data data/sw-pv-val --presence-rule row_contrast --no-synthetic --no-plots \
  --out $R/eval-side-new-kinds > $R/eval-side-new-kinds.log 2>&1
.venv/bin/station compare $R/eval-new-kinds $R/eval-side-new-kinds \
  --split docs/results/2026-11-30-threshold-counts/split-b1.json --out $R/two-cameras-new-kinds
mkdir -p $D/two-cameras
cp $R/two-cameras-new-kinds/* $D/two-cameras/
cp $R/eval-side-new-kinds/eval.md $D/two-cameras/eval-side.md
