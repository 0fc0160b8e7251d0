#!/bin/bash
# rule 54's set: fresh seed 1157, the shipped line (no panel variation), as rule 52's 1154
cd "$(dirname "$0")/../../.."  # the repository root
P="--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml"
for k in 0 1; do
  OMP_NUM_THREADS=1 .venv/bin/station render --out data/line-panel-heldout-1157 $P --count 400 --seed 1157 --defects 0.6 --heldout --visibility --shard $k/2 > runs/r54-r1157-$k.log 2>&1 &
done
wait
echo done > runs/r54-r1157.done
