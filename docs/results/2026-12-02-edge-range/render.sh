#!/bin/bash
# The edge-range fit's sets (plan.md), from anywhere; resumable (a finished sample is skipped). As rule 62's sets
# (docs/results/2026-11-29-finish-vary/render.sh), with each part's chamfer drawn 0-0.4 mm (--edge-mm 0,0.4):
#   render.sh train: seed 101's train split only (indices i % 10 >= 3: 630 of 900 parts), as data/line-ef-train
#   render.sh val:   seed 303's 600 validation parts, as data/line-ef-val (calibration of the fit and the look)
set -euo pipefail
cd "$(dirname "$0")/../../.."  # the repository root
P="--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml
   --config sim/presets/panel-vary.toml --config sim/presets/finish-vary.toml --edge-mm 0,0.4"
export OMP_NUM_THREADS=1
mkdir -p runs/c86
case $1 in
  train)  # 20 shards: those with k % 10 >= 3 are the train split's; 7 per process
    for half in 0 1; do
      (for j in 3 4 5 6 7 8 9; do
         k=$(( j + 10 * half ))
         .venv/bin/station render --out data/line-ef-train $P --count 900 --seed 101 --defects 0.4 \
           --defects-in-train --shard $k/20
       done) > runs/c86/render-train-$half.log 2>&1 &
    done
    wait;;
  val)
    for k in 0 1; do
      .venv/bin/station render --out data/line-ef-val $P --count 600 --seed 303 --defects 0.4 --validation \
        --shard $k/2 > runs/c86/render-val-$k.log 2>&1 &
    done
    wait;;
esac
