#!/bin/bash
# Plan 69's sets (plan.md), from anywhere; resumable (a finished sample is skipped). As rule 67's
# (docs/results/2026-12-02-edge-range/render.sh) with lobe.toml layered last:
#   render.sh train: seed 101's train split only (indices i % 10 >= 3: 630 of 900 parts), as data/line-lf-train
#   render.sh cal:   seed 303's 600 validation parts, as data/line-lf-val (calibration of the fit and the look)
#   render.sh val:   seed 303's 600 validation parts as built (panel drawn), as data/line-pv-val (the threshold),
#                    LANES processes (default 2)
set -euo pipefail
cd "$(dirname "$0")/../../.."  # the repository root
S=docs/results/2026-12-02-lobe-fit
B="--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml
   --config sim/presets/panel-vary.toml"
P="$B --config sim/presets/finish-vary.toml --edge-mm 0,0.4 --config $S/lobe.toml"
export OMP_NUM_THREADS=1
mkdir -p runs/c88
case $1 in
  train)  # 20 shards: those with k % 10 >= 3 are the train split's; 7 per process
    for half in 0 1; do
      (for j in 3 4 5 6 7 8 9; do
         k=$(( j + 10 * half ))
         .venv/bin/station render --out data/line-lf-train $P --count 900 --seed 101 --defects 0.4 \
           --defects-in-train --shard $k/20
       done) > runs/c88/render-train-$half.log 2>&1 &
    done
    wait;;
  cal)
    for k in 0 1; do
      .venv/bin/station render --out data/line-lf-val $P --count 600 --seed 303 --defects 0.4 --validation \
        --shard $k/2 > runs/c88/render-cal-$k.log 2>&1 &
    done
    wait;;
  val)
    n=${LANES:-2}
    for ((k = 0; k < n; k++)); do
      .venv/bin/station render --out data/line-pv-val $B --count 600 --seed 303 --defects 0.4 --validation \
        --shard $k/$n > runs/c88/render-val-$k.log 2>&1 &
    done
    wait;;
esac
