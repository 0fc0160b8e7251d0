#!/bin/sh
# The sets rule 28 ships F with, rendered after render-28.sh whatever its outcome (the cores would idle otherwise):
# F's training and validation sets at the shipped recipe's sizes (data/fp-train and data/fp-val hard-linked, then
# extended: same seeds, so their first samples are those), and the shipped model's held-out set, seed 1130.
# Run from the repository root; resumable: run again to finish.
set -e
V="--config sim/presets/line-polar.toml --config sim/presets/variation.toml"
F="$V --config docs/results/2026-11-27-dome-and-panel/dome-and-panel.toml"
two() {  # out, then render arguments
    out=$1; shift
    .venv/bin/station render "$@" --out "$out" --shard 0/2 > "runs/bf/$(basename "$out")-0.log" 2>&1 &
    .venv/bin/station render "$@" --out "$out" --shard 1/2 > "runs/bf/$(basename "$out")-1.log" 2>&1
    wait
}
# (started after render-28.sh had finished)
[ -e data/line-panel-train ] || cp -al data/fp-train data/line-panel-train
[ -e data/line-panel-val ] || cp -al data/fp-val data/line-panel-val
two data/line-panel-train $F --count 900 --seed 101 --defects 0.4 --defects-in-train
two data/line-panel-val $F --count 600 --seed 303 --defects 0.4 --validation
two data/line-panel-heldout $F --count 400 --seed 1130 --defects 0.6 --heldout
