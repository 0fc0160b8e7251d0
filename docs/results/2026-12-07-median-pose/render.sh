#!/usr/bin/env bash
# plan.md's fresh sets, one after another, each resumable in two shards; run from the repository's root.
set -euo pipefail
T=docs/results/2026-12-06-turn-check
"$T/render.sh" "-20 1232 $T/turned-20.toml"
export OMP_NUM_THREADS=1
for k in 0 1; do
    .venv/bin/station render --out data/square-1233 --config sim/presets/line-polar.toml \
        --config sim/presets/variation.toml --config sim/presets/panel.toml \
        --count 400 --seed 1233 --defects 0.6 --heldout --shard "$k/2" &
done
wait
"$T/render.sh" "20 1234 docs/results/2026-12-06-turns/turned20.toml"
