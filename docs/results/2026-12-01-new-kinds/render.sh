#!/usr/bin/env bash
# The new kinds' held-out set (plan.md): seed 1179, 400 parts as make model renders its held-out set, on the line as
# built, with blisters and debris only (types.toml). Resumable; about 20 min on 2 cores.
set -euo pipefail
D=docs/results/2026-12-01-new-kinds
export OMP_NUM_THREADS=1
P=(--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml)
for k in 0 1; do
    .venv/bin/station render --out data/new-kinds-1179 "${P[@]}" --config $D/types.toml --count 400 --seed 1179 \
        --defects 0.6 --heldout --visibility --shard $k/2 &
done
wait
