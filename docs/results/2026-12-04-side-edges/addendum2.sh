#!/usr/bin/env bash
# plan.md's addendum 2: seed 1191 as built, the side camera's twins, the files and thresholds of run.sh. Resumable.
source "$(dirname "$0")/common.sh"
for k in 0 1; do
    .venv/bin/station render --out data/sw-heldout-1191 "${P[@]}" "${S[@]}" --count 400 --seed 1191 --defects 0.6 \
        --heldout --shard $k/2 > $R/render-1191-$k.log 2>&1 &
done
wait
ablation_line 1191
side data/sw-heldout-1191 1191
pair 1191
