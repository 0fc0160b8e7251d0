#!/bin/sh
# Rule 33's renders (run from the repository root; resumable: a killed run picks up where it stopped, about 95 min
# on 2 cores in all). The shipped line's held-out set of seed 1133 first (a new untouched set, also for later rules),
# then Q's training, validation and held-out sets.
set -e
V="--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml"
Q="$V --config docs/results/2026-11-27-light-plate/plate.toml"
mkdir -p runs/lp
two() {  # name, then station render's arguments: both shards, one per core
    name=$1; shift
    .venv/bin/station render "$@" --out data/$name --shard 0/2 > runs/lp/$name-0.log 2>&1 &
    .venv/bin/station render "$@" --out data/$name --shard 1/2 > runs/lp/$name-1.log 2>&1
    wait
}
two line-panel-heldout-1133 $V --count 400 --seed 1133 --defects 0.6 --heldout --visibility
two lp-train $Q --count 400 --seed 101 --defects 0.4 --defects-in-train
two lp-val $Q --count 300 --seed 303 --defects 0.4 --validation
two lp-heldout $Q --count 400 --seed 1133 --defects 0.6 --heldout
