#!/bin/sh
# Rule 30's renders (run from the repository root; resumable: a killed run picks up where it stopped).
# Step 1: rule 25's 100 defective parts (seed 919) under Q; the shipped line's are data/bf-check-F (rule 26's
# render.sh). Then: python docs/results/2026-11-27-bright-field/contrast.py data/bf-check-F data/fl-check
# Step 2 (STEP=2): Q's training, validation and held-out sets (the seeds of the shipped line's sets, fewer parts).
set -e
V="--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml"
Q="$V --config docs/results/2026-11-27-front-light/front-light.toml"
mkdir -p runs/fl
two() {  # name, then station render's arguments: both shards, one per core
    name=$1; shift
    .venv/bin/station render $Q "$@" --out data/$name --shard 0/2 > runs/fl/$name-0.log 2>&1 &
    .venv/bin/station render $Q "$@" --out data/$name --shard 1/2 > runs/fl/$name-1.log 2>&1
    wait
}
if [ "${STEP:-1}" = 1 ]; then
    two fl-check --count 100 --seed 919 --defects 1.0 --heldout
else
    two fl-train --count 400 --seed 101 --defects 0.4 --defects-in-train
    two fl-val --count 300 --seed 303 --defects 0.4 --validation
    two fl-heldout --count 400 --seed 1131 --defects 0.6 --heldout
fi
