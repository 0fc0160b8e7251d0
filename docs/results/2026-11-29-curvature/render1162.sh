#!/bin/bash
# the shipped file's report set (rule 60): fresh seed 1162, the shipped line as built (no panel variation), as seeds 1154-1161
cd /work/main
P="--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml"
for k in 0 1; do
  OMP_NUM_THREADS=1 .venv/bin/station render --out data/line-panel-heldout-1162 $P --count 400 --seed 1162 --defects 0.6 --heldout --visibility --shard $k/2 > runs/r59/render-1162-$k.log 2>&1 &
done
wait
echo done > runs/r59/render1162.done
