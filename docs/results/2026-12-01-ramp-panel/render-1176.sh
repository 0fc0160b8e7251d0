#!/usr/bin/env bash
# The ramp's twins of data/line-pv-val-1176 (stop 73's render-val.sh, ramp.toml layered last). ~15 min on 2 cores.
set -euo pipefail
D=docs/results/2026-12-01-ramp-panel
export OMP_NUM_THREADS=1
P=(--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml
   --config sim/presets/panel-vary.toml --config $D/ramp.toml)
for k in 0 1; do
    .venv/bin/station render --out data/ramp-pv-val-1176 "${P[@]}" --count 600 --seed 1176 --defects 0.4 \
        --validation --shard $k/2 &
done
wait
