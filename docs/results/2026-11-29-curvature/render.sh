#!/bin/bash
# A fresh held-out seed of the shipped line as built (no panel variation), as seeds 1154-1159: rule 59's 1160,
# rule 60's 1161, the shipped file's report set 1162 (each rendered as `render.sh SEED` in this stop; resumable).
# Usage, from anywhere: render.sh SEED
set -euo pipefail
cd "$(dirname "$0")/../../.."  # the repository root
SEED=$1
P="--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml"
mkdir -p runs/r59
for k in 0 1; do
  OMP_NUM_THREADS=1 .venv/bin/station render --out data/line-panel-heldout-$SEED $P --count 400 --seed $SEED \
    --defects 0.6 --heldout --visibility --shard $k/2 > runs/r59/render-$SEED-$k.log 2>&1 &
done
wait
