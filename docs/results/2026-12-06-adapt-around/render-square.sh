#!/usr/bin/env bash
# After the reading (not part of the plan's rule): seed 1212's 600 parts seen square, to tell which of the shipped
# file's good parts rejected turned it rejects square too. Resumable, two shards; run from the repository's root.
set -euo pipefail
export OMP_NUM_THREADS=1
for k in 0 1; do
    .venv/bin/station render --out data/adapt-1212 --config sim/presets/line-polar.toml \
        --config sim/presets/variation.toml --config sim/presets/panel.toml --count 600 --seed 1212 --defects 0.3 \
        --heldout --shard "$k/2" &
done
wait
