#!/usr/bin/env bash
# plan-2.md's set T12: seed 1221, 300 parts, 40 % defective, every part test, the camera turned 12 degrees.
# Resumable, two shards; run from the repository's root.
set -euo pipefail
export OMP_NUM_THREADS=1
for k in 0 1; do
    .venv/bin/station render --out data/turned12-1221 --config sim/presets/line-polar.toml \
        --config sim/presets/variation.toml --config sim/presets/panel.toml \
        --config docs/results/2026-12-06-turns/turned12.toml --count 300 --seed 1221 --defects 0.4 --heldout \
        --shard "$k/2" &
done
wait
