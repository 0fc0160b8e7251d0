#!/bin/sh
# Rule 33, read afterwards: four of the highest-scoring good parts of Q's held-out set and two typical ones, rendered
# again at 64 samples per pixel (the same draws: --shard I/400 renders part I only), then Q's scores of them.
set -e
V="--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml"
for i in 137 42 329 172 167 202; do
    .venv/bin/station render $V --config docs/results/2026-11-27-light-plate/plate.toml --count 400 --seed 1133 \
        --defects 0.6 --heldout --spp 64 --out data/lp-spp64 --shard $i/400
done
.venv/bin/python docs/results/2026-11-27-light-plate/after.py runs/lp/Q data/lp-spp64 --rescore
