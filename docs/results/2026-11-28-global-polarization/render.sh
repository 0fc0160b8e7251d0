#!/bin/sh
# Rule 37's renders (run from the repository root; resumable): the training set as scripts/make-model.sh renders it
# (the shipped model's; the validation set data/line-panel-val as rules 35-36 rendered it), then the new held-out
# set of seed 1134.
set -e
V="--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml"
mkdir -p runs/gp
two() {  # name, then station render's arguments: both shards, one per core
    name=$1; shift
    .venv/bin/station render "$@" --out data/$name --shard 0/2 > runs/gp/$name-0.log 2>&1 &
    .venv/bin/station render "$@" --out data/$name --shard 1/2 > runs/gp/$name-1.log 2>&1
    wait
}
two line-panel-train $V --count 900 --seed 101 --defects 0.4 --defects-in-train
two line-panel-heldout-1134 $V --count 400 --seed 1134 --defects 0.6 --heldout
