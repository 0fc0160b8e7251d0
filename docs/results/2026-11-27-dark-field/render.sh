#!/bin/sh
# Rule 24's renders, two shards at a time (run from the repository root; resumable: run again to finish).
set -e
V="--config sim/presets/line-polar.toml --config sim/presets/variation.toml"
R="$V --config docs/results/2026-11-27-dark-field/dark-field-ring.toml --spp 32"
two() {  # out, then render arguments
    out=$1; shift
    .venv/bin/station render "$@" --out "$out" --shard 0/2 > "runs/df/$(basename "$out")-0.log" 2>&1 &
    .venv/bin/station render "$@" --out "$out" --shard 1/2 > "runs/df/$(basename "$out")-1.log" 2>&1
    wait
}
while pgrep -f "station render" > /dev/null; do sleep 10; done  # a run already under way
two data/df-ring-train $R --count 400 --seed 101 --defects 0.4 --defects-in-train
two data/df-ring-val $R --count 150 --seed 303 --defects 0.4 --validation
two data/df-dome-heldout $V --count 240 --seed 858 --defects 0.6 --heldout
two data/df-ring-heldout $R --count 240 --seed 858 --defects 0.6 --heldout
