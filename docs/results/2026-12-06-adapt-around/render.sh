#!/usr/bin/env bash
# plan.md's set T: seed 1212, 600 parts, 30 % defective, the camera turned 5 degrees. Resumable, two shards; run from
# the repository's root.
set -euo pipefail
export OMP_NUM_THREADS=1
for k in 0 1; do
    .venv/bin/station render --out data/adapt-1212-turned5 --config sim/presets/line-polar.toml \
        --config sim/presets/variation.toml --config sim/presets/panel.toml \
        --config docs/results/2026-12-05-seen-edges/turned5.toml --count 600 --seed 1212 --defects 0.3 --heldout \
        --shard "$k/2" &
done
wait
