#!/usr/bin/env bash
# plan.md's sets T4 (seed 1218, the camera turned 4 degrees) and T8 (seed 1219, 8 degrees): 300 parts each, 40 %
# defective, every part test; or the sets named as "DEGREES SEED" arguments (render-2.sh). Resumable, two shards each;
# run from the repository's root.
set -euo pipefail
export OMP_NUM_THREADS=1
D=docs/results/2026-12-06-turns
[ $# -gt 0 ] || set -- "4 1218" "8 1219"
for set in "$@"; do
    read -r a seed <<< "$set"
    for k in 0 1; do
        .venv/bin/station render --out "data/turned$a-$seed" --config sim/presets/line-polar.toml \
            --config sim/presets/variation.toml --config sim/presets/panel.toml --config "$D/turned$a.toml" \
            --count 300 --seed "$seed" --defects 0.4 --heldout --shard "$k/2" &
    done
    wait
done
