#!/usr/bin/env bash
# plan.md's fresh sets: T20 (seed 1227, the camera turned 20 degrees) and T25 (seed 1228, 25 degrees), 300 parts each,
# 40 % defective, every part test, rendered as the turned sets before (../2026-12-06-turns/render.sh); or the sets
# named as "DEGREES SEED TOML" arguments (render-2.sh, render-3.sh). Resumable, two shards each, one set after another;
# run from the repository's root.
set -euo pipefail
export OMP_NUM_THREADS=1
D=docs/results/2026-12-06-turn-check
[ $# -gt 0 ] || set -- "20 1227 docs/results/2026-12-06-turns/turned20.toml" "25 1228 $D/turned25.toml"
for set in "$@"; do
    read -r a seed toml <<< "$set"
    for k in 0 1; do
        .venv/bin/station render --out "data/turned$a-$seed" --config sim/presets/line-polar.toml \
            --config sim/presets/variation.toml --config sim/presets/panel.toml --config "$toml" \
            --count 300 --seed "$seed" --defects 0.4 --heldout --shard "$k/2" &
    done
    wait
done
