#!/usr/bin/env bash
# plan-4.md: the second camera's stripes, precision reading on seed 303's first 80 parts. Resumable.
set -euo pipefail
cd "$(dirname "$0")/../../.."  # the repository root
D=docs/results/2026-12-01-deflectometry
R=runs/c80
mkdir -p $R
export OMP_NUM_THREADS=1 PYTHONPATH=.
P=(--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml
   --config sim/presets/panel-vary.toml --config sim/presets/side-view.toml)
for ph in 0 90; do
    for k in 0 1; do
        .venv/bin/station render --out data/sfr$ph-pv-val "${P[@]}" --config $D/side-fringe-$ph.toml --count 80 \
            --seed 303 --defects 0.4 --validation --no-ground-truth --shard $k/2 > $R/render-sfr$ph-$k.log 2>&1 &
    done
    wait
done
.venv/bin/python $D/quadrature.py data/sw-pv-val data/sfr0-pv-val data/sfr90-pv-val data/sfq-pv-val > $R/sfq.log
.venv/bin/python $D/precision.py data/sfq-pv-val data/sw-pv-val 40 31.4 > $D/precision-side.txt
.venv/bin/python $D/precision.py data/sfq-pv-val data/sw-pv-val 40 31.4 position >> $D/precision-side.txt
# After plan-4's reading, not deciding (precision-per-part.py): each part's own prediction, the flat dome's stripes
# and the panel's (run-3.sh's quadrature makes data/fq-pv-val).
.venv/bin/python $D/precision-per-part.py data/sfq-pv-val data/sw-pv-val 31.4 > $D/precision-per-part.txt
.venv/bin/python $D/precision-per-part.py data/fq-pv-val data/line-pv-val 30 >> $D/precision-per-part.txt
