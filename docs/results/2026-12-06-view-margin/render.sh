#!/usr/bin/env bash
# plan.md's sets: T (seed 1211's first 200 parts, the camera turned 5 degrees) and S (seed 1211, 400 parts, square).
# Resumable, two shards each; run from the repository's root.
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
render data/margin-1211-turned5 200 1211 --config docs/results/2026-12-05-seen-edges/turned5.toml
render data/margin-1211 400 1211
