#!/usr/bin/env bash
# plan.md's set S: fresh seed 1220, 400 parts, 60 % defective, every part test, the line as built with the five kinds
# shaped otherwise (shaped-otherwise.toml). Resumable, two shards; run from the repository's root.
set -euo pipefail
export OMP_NUM_THREADS=1
for k in 0 1; do
    .venv/bin/station render --out data/shaped-otherwise-1220 --config sim/presets/line-polar.toml \
        --config sim/presets/variation.toml --config sim/presets/panel.toml \
        --config docs/results/2026-12-06-shaped-otherwise/shaped-otherwise.toml --count 400 --seed 1220 \
        --defects 0.6 --heldout --shard "$k/2" &
done
wait
