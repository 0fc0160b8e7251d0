#!/usr/bin/env bash
# plan.md's addendum: seed 1192 with every edge rounded 0.3 mm, both cameras, the files and thresholds of run.sh.
# Resumable (renders resume per sample; each report is kept). Run after run.sh.
source "$(dirname "$0")/common.sh"
H=(--count 400 --seed 1192 --defects 0.6 --heldout --edge-mm 0.3 --edge-shape round
   --config docs/results/2026-12-02-edge-range/no-chips.toml)
for k in 0 1; do
    (.venv/bin/station render --out data/sw-heldout-1192-r3 "${P[@]}" "${H[@]}" "${S[@]}" --shard $k/2
     .venv/bin/station render --out data/line-heldout-1192-r3 "${P[@]}" "${H[@]}" --shard $k/2) \
        > $R/render-r3-$k.log 2>&1 &
done
wait
line data/line-heldout-1192-r3 1192-r3 &
side data/sw-heldout-1192-r3 1192-r3 &
wait
pair 1192-r3
.venv/bin/python $D/plot.py
