#!/usr/bin/env bash
# plan.md: the two-camera station as built on seed 1184. Resumable (renders resume; make side-model resumes; each
# report is kept).
set -euo pipefail
cd "$(dirname "$0")/../../.."  # the repository root
R=runs/c83
D=docs/results/2026-12-02-two-cameras-1184
mkdir -p $R
export OMP_NUM_THREADS=1
P=(--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml)
# the side camera's frames of seed 1184 on one core, beside make side-model (its fit runs on one core)
.venv/bin/station render --out data/sw-heldout-1184 "${P[@]}" --config sim/presets/side-view.toml --count 400 \
    --seed 1184 --defects 0.6 --heldout > $R/render-sw-heldout-1184.log 2>&1 &
scripts/make-side-model.sh > $R/make-side-model.log 2>&1
wait
E=(--no-synthetic --no-plots)
[ -f $R/eval-line-1184/scores.csv ] || .venv/bin/station eval --model model/weights/default \
    --data data/line-panel-heldout-1184 --val-data data/line-pv-val "${E[@]}" --out $R/eval-line-1184 \
    > $R/eval-line-1184.log 2>&1 &
[ -f $R/eval-side-1184/scores.csv ] || .venv/bin/station eval --model runs/make-side-model/side \
    --data data/sw-heldout-1184 --val-data data/sw-pv-val --presence-rule row_contrast "${E[@]}" \
    --out $R/eval-side-1184 > $R/eval-side-1184.log 2>&1 &
wait
.venv/bin/station compare $R/eval-line-1184 $R/eval-side-1184 --split runs/make-side-model/split.json \
    --out $R/two-cameras-1184
mkdir -p $D/eval
cp $R/two-cameras-1184/two-cameras.md $D/two-cameras-1184.md
cp runs/make-side-model/split.json $D/split.json
cp $R/eval-side-1184/eval.md $D/eval/eval-side-1184.md
sha256sum runs/make-side-model/side.pt > $D/side.sha256
