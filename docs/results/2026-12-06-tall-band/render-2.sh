#!/usr/bin/env bash
# plan-2.md's sets, rendered after the plan was committed: S (seed 1209, square), R and R2 (the same parts, the camera
# turned 5 and 2 degrees), W (seed 1210, warps only). Resumable, two shards each; run from the repository's root.
set -euo pipefail
export OMP_NUM_THREADS=1
P=(--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml)
render() {  # render OUT COUNT SEED [ARGS]
    local out=$1 count=$2 seed=$3; shift 3
    for k in 0 1; do
        .venv/bin/station render --out "$out" "${P[@]}" "$@" --count "$count" --seed "$seed" --defects 0.6 --heldout \
            --shard "$k/2" &
    done
    wait
}
render data/tall-1209 400 1209 --visibility
render data/tall-1209-turned5 400 1209 --config docs/results/2026-12-05-seen-edges/turned5.toml
render data/tall-1209-turned2 400 1209 --config docs/results/2026-12-05-seen-edges/turned2.toml
render data/tall-warps-1210 200 1210 --config docs/results/2026-12-05-moulding-kinds/warp.toml
