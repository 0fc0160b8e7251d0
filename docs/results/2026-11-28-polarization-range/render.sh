#!/bin/sh
# Rule 38's render (run from the repository root; resumable): the new held-out set of seed 1136, both shards, one
# per core. (The training and validation sets are rule 37's: data/line-panel-train, data/line-panel-val.)
set -e
V="--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml"
mkdir -p runs/r38
for i in 0 1; do
    .venv/bin/station render $V --count 400 --seed 1136 --defects 0.6 --heldout --out data/line-panel-heldout-1136 \
        --shard $i/2 > runs/r38/r1136-$i.log 2>&1 &
done
wait
