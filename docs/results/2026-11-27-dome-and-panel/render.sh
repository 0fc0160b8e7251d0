#!/bin/sh
# Rule 26's renders (run from the repository root; resumable). Step 1: rule 25's 100 defective parts (seed 919)
# under F; then `python docs/results/2026-11-27-bright-field/contrast.py data/bf-check-D data/bf-check-B data/bf-check-F`
# (rule 25's render.sh makes the D and B sets).
set -e
V="--config sim/presets/line-polar.toml --config sim/presets/variation.toml"
F="$V --config docs/results/2026-11-27-dome-and-panel/dome-and-panel.toml"
mkdir -p runs/bf
.venv/bin/station render $F --count 100 --seed 919 --defects 1.0 --heldout --out data/bf-check-F --shard 0/2 \
    > runs/bf/bf-check-F-0.log 2>&1 &
.venv/bin/station render $F --count 100 --seed 919 --defects 1.0 --heldout --out data/bf-check-F --shard 1/2 \
    > runs/bf/bf-check-F-1.log 2>&1
wait
