#!/bin/sh
# Rule 28's renders, two shards at a time (run from the repository root; resumable: run again to finish).
set -e
V="--config sim/presets/line-polar.toml --config sim/presets/variation.toml"
F="$V --config docs/results/2026-11-27-dome-and-panel/dome-and-panel.toml"
mkdir -p runs/bf
two() {  # out, then render arguments
    out=$1; shift
    .venv/bin/station render "$@" --out "$out" --shard 0/2 > "runs/bf/$(basename "$out")-0.log" 2>&1 &
    .venv/bin/station render "$@" --out "$out" --shard 1/2 > "runs/bf/$(basename "$out")-1.log" 2>&1
    wait
}
two data/fp-confirm $F --count 400 --seed 1129 --defects 0.6 --heldout
two data/df-confirm $V --count 400 --seed 1129 --defects 0.6 --heldout
