#!/bin/sh
# Rule 32's renders (run from the repository root; resumable: a killed run picks up where it stopped, about 90 min
# on 2 cores in all). The shipped line's held-out set of seed 1132 first (a new untouched set, also for later rules),
# then R's training, validation and held-out sets.
set -e
V="--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml"
R="$V --config docs/results/2026-11-27-fringe-panel/fringe.toml"
mkdir -p runs/fr
two() {  # name, then station render's arguments: both shards, one per core
    name=$1; shift
    .venv/bin/station render "$@" --out data/$name --shard 0/2 > runs/fr/$name-0.log 2>&1 &
    .venv/bin/station render "$@" --out data/$name --shard 1/2 > runs/fr/$name-1.log 2>&1
    wait
}
two line-panel-heldout-1132 $V --count 400 --seed 1132 --defects 0.6 --heldout --visibility
two fr-train $R --count 400 --seed 101 --defects 0.4 --defects-in-train
two fr-val $R --count 300 --seed 303 --defects 0.4 --validation
two fr-heldout $R --count 400 --seed 1132 --defects 0.6 --heldout
