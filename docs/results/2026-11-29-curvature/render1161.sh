#!/bin/bash
# rule 60's set: fresh seed 1161, the shipped line as built (no panel variation), as seeds 1154-1160
cd /work/main
P="--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml"
for k in 0 1; do
  OMP_NUM_THREADS=1 .venv/bin/station render --out data/line-panel-heldout-1161 $P --count 400 --seed 1161 --defects 0.6 --heldout --visibility --shard $k/2 > runs/r59/render-1161-$k.log 2>&1 &
done
wait
echo done > runs/r59/render1161.done
