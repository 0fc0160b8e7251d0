#!/usr/bin/env bash
# plan-3.md's fresh sets: T-12 (seed 1230) and T-20 (seed 1231), the camera turned 12 and 20 degrees the other way,
# 300 parts each, 40 % defective, every part test, rendered as render.sh's; both at once, two shards each. Resumable;
# run from the repository's root.
set -euo pipefail
export OMP_NUM_THREADS=1
D=docs/results/2026-12-06-turn-check
for set in "-12 1230" "-20 1231"; do
    read -r a seed <<< "$set"
    for k in 0 1; do
        .venv/bin/station render --out "data/turned$a-$seed" --config sim/presets/line-polar.toml \
            --config sim/presets/variation.toml --config sim/presets/panel.toml --config "$D/turned$a.toml" \
            --count 300 --seed "$seed" --defects 0.4 --heldout --shard "$k/2" &
    done
done
wait
