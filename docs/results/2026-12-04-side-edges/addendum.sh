#!/usr/bin/env bash
# plan.md's addendum: seed 1192 with every edge rounded 0.3 mm, both cameras, the files and thresholds of run.sh.
# Resumable (renders resume per sample; each report is kept). Run after run.sh.
set -euo pipefail
cd "$(dirname "$0")/../../.."  # the repository root
R=runs/c98
D=docs/results/2026-12-04-side-edges
export OMP_NUM_THREADS=1
P=(--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml)
S=(--config sim/presets/side-view.toml)
H=(--count 400 --seed 1192 --defects 0.6 --heldout --edge-mm 0.3 --edge-shape round
   --config docs/results/2026-12-02-edge-range/no-chips.toml)
for k in 0 1; do
    (.venv/bin/station render --out data/sw-heldout-1192-r3 "${P[@]}" "${H[@]}" "${S[@]}" --shard $k/2
     .venv/bin/station render --out data/line-heldout-1192-r3 "${P[@]}" "${H[@]}" --shard $k/2) \
        > $R/render-r3-$k.log 2>&1 &
done
wait
E=(--no-synthetic --no-plots)
[ -f $R/eval-line-1192-r3/scores.csv ] || .venv/bin/station eval --model model/weights/default \
    --data data/line-heldout-1192-r3 --val-data data/line-pv-val "${E[@]}" --out $R/eval-line-1192-r3 \
    > $R/eval-line-1192-r3.log 2>&1 &
[ -f $R/eval-side-1192-r3/scores.csv ] || .venv/bin/station eval --model runs/make-side-model/side \
    --data data/sw-heldout-1192-r3 --val-data data/sw-pv-val --presence-rule row_contrast "${E[@]}" \
    --out $R/eval-side-1192-r3 > $R/eval-side-1192-r3.log 2>&1 &
wait
.venv/bin/station compare $R/eval-line-1192-r3 $R/eval-side-1192-r3 --split runs/make-side-model/split.json \
    --out $R/two-cameras-1192-r3
cp $R/two-cameras-1192-r3/two-cameras.md $D/two-cameras-1192-r3.md
cp $R/two-cameras-1192-r3/two-cameras.json $D/two-cameras-1192-r3.json
cp $R/eval-side-1192-r3/eval.md $D/eval/eval-side-1192-r3.md
cp $R/eval-line-1192-r3/eval.md $D/eval/eval-line-1192-r3.md
.venv/bin/python $D/plot.py
