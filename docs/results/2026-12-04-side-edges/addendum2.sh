#!/usr/bin/env bash
# plan.md's addendum 2: seed 1191 as built, the side camera's twins, the files and thresholds of run.sh. Resumable.
set -euo pipefail
cd "$(dirname "$0")/../../.."  # the repository root
R=runs/c98
D=docs/results/2026-12-04-side-edges
export OMP_NUM_THREADS=1
P=(--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml)
for k in 0 1; do
    .venv/bin/station render --out data/sw-heldout-1191 "${P[@]}" --config sim/presets/side-view.toml --count 400 \
        --seed 1191 --defects 0.6 --heldout --shard $k/2 > $R/render-1191-$k.log 2>&1 &
done
wait
mkdir -p $R/eval-line-1191
cp $D/../2026-12-04-priors-ablation/shipped/eval-E63-1191/scores.csv \
   $D/../2026-12-04-priors-ablation/shipped/eval-E63-1191/eval.json $R/eval-line-1191/  # as read there
[ -f $R/eval-side-1191/scores.csv ] || .venv/bin/station eval --model runs/make-side-model/side \
    --data data/sw-heldout-1191 --val-data data/sw-pv-val --presence-rule row_contrast --no-synthetic --no-plots \
    --out $R/eval-side-1191 > $R/eval-side-1191.log 2>&1
.venv/bin/station compare $R/eval-line-1191 $R/eval-side-1191 --split runs/make-side-model/split.json \
    --out $R/two-cameras-1191
cp $R/two-cameras-1191/two-cameras.md $D/two-cameras-1191.md
cp $R/two-cameras-1191/two-cameras.json $D/two-cameras-1191.json
cp $R/eval-side-1191/eval.md $D/eval/eval-side-1191.md
