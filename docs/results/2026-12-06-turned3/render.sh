#!/usr/bin/env bash
# plan.md's set R3: seed 1217, 300 parts, 40 % defective, the camera turned 3 degrees. Resumable, two shards; run
# from the repository's root.
set -euo pipefail
export OMP_NUM_THREADS=1
for k in 0 1; do
    .venv/bin/station render --out data/turned3-1217 --config sim/presets/line-polar.toml \
        --config sim/presets/variation.toml --config sim/presets/panel.toml \
        --config docs/results/2026-12-06-turned3/turned3.toml --count 300 --seed 1217 --defects 0.4 --heldout \
        --shard "$k/2" &
done
wait
