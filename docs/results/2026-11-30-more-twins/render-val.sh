#!/bin/bash
# check 73: a second validation twin set, seed 1176, as make-side-model.sh renders seed 303's
set -euo pipefail
cd /work/main
export OMP_NUM_THREADS=1
P="--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml --config sim/presets/panel-vary.toml"
for s in line-pv-val:"$P" sw-pv-val:"$P --config sim/presets/side-view.toml"; do
  name=${s%%:*}; cfg=${s#*:}
  for k in 0 1; do
    .venv/bin/station render --out data/$name-1176 $cfg --count 600 --seed 1176 --defects 0.4 --validation \
      --shard $k/2 > runs/c73/render-$name-$k.log 2>&1 &
  done
  wait
done
echo done > runs/c73/val-done
