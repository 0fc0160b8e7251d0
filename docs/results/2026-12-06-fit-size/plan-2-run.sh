#!/usr/bin/env bash
# plan-2.md, as run: the recipe on 1,800 training parts (resumable: rerun it after an interruption) and H, seed 1216,
# beside it; then the reading. Run from the repository's root. As run, the recipe stopped once at its held-out
# render (H, rendered without --visibility, refused the recipe's --visibility until 430e77af) and was run again; it
# resumed. The shipped file's evaluation ran beside the recipe's variation fit.
set -euo pipefail
export OMP_NUM_THREADS=1
P=(--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml)
TRAIN_COUNT=1800 DATA=data/line-ef-train-1800 SHIP=0 HOLDOUT_TYPES=" " NEW_KINDS_COUNT=0 RUNS=runs/make-model-1800 \
    HELDOUT=data/h-1216 HELDOUT_SEED=1216 make model > runs/make-model-1800.log 2>&1 &
for k in 0 1; do
    .venv/bin/station render --out data/h-1216 "${P[@]}" --count 400 --seed 1216 --defects 0.6 --heldout \
        --shard "$k/2" &
done
wait
D=docs/results/2026-12-06-fit-size
.venv/bin/python $D/paired.py model/weights/default runs/make-model-1800/band-look data/h-1216 | tee $D/plan-2-paired.txt
.venv/bin/station eval --model model/weights/default --data data/h-1216 --val-data data/line-pv-val \
    --out $D/eval-2/shipped
cp -r runs/make-model-1800/eval-band-look $D/eval-2/new
