#!/bin/sh
# Rule 34's renders (run from the repository root; resumable: a killed run picks up where it stopped). Two frames
# per part (the dome's halves 0 and 180), both shards on the two cores.
set -e
V="--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml"
S="$V --config docs/results/2026-11-25-gradient-dome/gradient-dome.toml --dome-segments 0,180"
mkdir -p runs/pst
two() {  # name, then station render's arguments: both shards, one per core
    name=$1; shift
    .venv/bin/station render $S "$@" --out data/$name --shard 0/2 > runs/pst/$name-0.log 2>&1 &
    .venv/bin/station render $S "$@" --out data/$name --shard 1/2 > runs/pst/$name-1.log 2>&1
    wait
}
two pst-train --count 360 --seed 141 --defects 0
two pst-val --count 200 --seed 343 --defects 0.4 --validation
two pst-heldout --count 400 --seed 1135 --defects 0.6 --heldout
