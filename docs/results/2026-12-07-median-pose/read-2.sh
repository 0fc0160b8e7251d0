#!/usr/bin/env bash
# plan-2.md's set and read: T+20' (seed 1235, the camera turned +20 degrees, 400 parts), rendered resumably in two
# shards, then A against B, paired, each at its own threshold; run from the repository's root.
set -euo pipefail
export OMP_NUM_THREADS=1 PYTHONPATH=.
pids=()
for k in 0 1; do
    .venv/bin/station render --out data/turned20-1235 --config sim/presets/line-polar.toml \
        --config sim/presets/variation.toml --config sim/presets/panel.toml \
        --config docs/results/2026-12-06-turns/turned20.toml \
        --count 400 --seed 1235 --defects 0.4 --heldout --shard "$k/2" & pids+=($!)
done
for p in "${pids[@]}"; do wait "$p"; done  # a shard that fails stops the read (a bare wait did not: read-2-partial.txt)
.venv/bin/python docs/results/2026-12-06-fit-size/paired.py runs/pose-1800-A/band-look runs/pose-1800/band-look \
    data/turned20-1235
