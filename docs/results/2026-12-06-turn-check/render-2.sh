#!/usr/bin/env bash
# plan-2.md's fresh set: T-20 (seed 1229, the camera turned 20 degrees the other way), 300 parts, 40 % defective, every
# part test, rendered as render.sh's. Resumable, two shards; run from the repository's root.
set -euo pipefail
export OMP_NUM_THREADS=1
D=docs/results/2026-12-06-turn-check
for k in 0 1; do
    .venv/bin/station render --out data/turned-20-1229 --config sim/presets/line-polar.toml \
        --config sim/presets/variation.toml --config sim/presets/panel.toml --config "$D/turned-20.toml" \
        --count 300 --seed 1229 --defects 0.4 --heldout --shard "$k/2" &
done
wait
