#!/bin/sh
# Rule 25's renders (run from the repository root; resumable: run again to finish). Step 1, the contrast check:
# the same 100 defective parts (seed 919) under the shipped line (D) and the panel line (B); then
# `python docs/results/2026-11-27-bright-field/contrast.py data/bf-check-D data/bf-check-B`.
# Step 2: rule 24's sets under B (D's are rule 24's: data/df-dome-train, df-dome-val, df-dome-heldout).
set -e
V="--config sim/presets/line-polar.toml --config sim/presets/variation.toml"
B="$V --config docs/results/2026-11-27-bright-field/bright-field.toml"
mkdir -p runs/bf
two() {  # out, then render arguments
    out=$1; shift
    .venv/bin/station render "$@" --out "$out" --shard 0/2 > "runs/bf/$(basename "$out")-0.log" 2>&1 &
    .venv/bin/station render "$@" --out "$out" --shard 1/2 > "runs/bf/$(basename "$out")-1.log" 2>&1
    wait
}
two data/bf-check-D $V --count 100 --seed 919 --defects 1.0 --heldout
two data/bf-check-B $B --count 100 --seed 919 --defects 1.0 --heldout
two data/bf-train $B --count 400 --seed 101 --defects 0.4 --defects-in-train
two data/bf-val $B --count 150 --seed 303 --defects 0.4 --validation
two data/bf-heldout $B --count 240 --seed 858 --defects 0.6 --heldout
