#!/bin/bash
# Made before check 69 (plan.md), for it: check 67's model S recipe on the wide dome's sets (W2 -> WS). As run from
# runs/c68 at the end of stop 68; resumable (a set's sample or a fit is kept).
set -euo pipefail
cd "$(dirname "$0")/../../.."  # the repository root
R=runs/c68
mkdir -p $R
export OMP_NUM_THREADS=1
V="--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml"
for k in 0 1; do  # the calibration set: the validation parts (seed 303) under the finish variation too
  .venv/bin/station render --out data/sw-pf-val $V --config sim/presets/panel-vary.toml \
    --config sim/presets/finish-vary.toml --config sim/presets/side-view.toml --count 600 --seed 303 --defects 0.4 \
    --validation --shard $k/2 > $R/render-pf-val-$k.log 2>&1 &
done
wait
[ -f $R/W2.json ] || .venv/bin/station variation --model runs/r52/F/default --refit --data data/sw-train \
  --val-data data/sw-pf-val --decision variation --out $R/W2 > $R/W2.log 2>&1
if [ ! -f $R/WS.json ]; then
  .venv/bin/station residual --model $R/W2 --data data/sw-train --val-data data/sw-pf-val --members 1 \
    --steps 3000 --second-look --out $R/WS-cal > $R/WS.log 2>&1
  .venv/bin/station threshold --model $R/WS-cal --data data/sw-pv-val >> $R/WS.log 2>&1
  .venv/bin/python -c "import sys; from model.draem.checkpoint import copy_checkpoint; copy_checkpoint(*sys.argv[1:])" \
    $R/WS-cal $R/WS
fi
