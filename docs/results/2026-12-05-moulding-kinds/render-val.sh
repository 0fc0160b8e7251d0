#!/usr/bin/env bash
# screen-plan.md: a validation set of warped parts, seed 1199, 300 parts rendered as make model renders its VAL set
# (the line, the panel drawn per part; every sample val), warp only. Resumable; about 10 min on 2 cores.
set -euo pipefail
D=docs/results/2026-12-05-moulding-kinds
export OMP_NUM_THREADS=1
P=(--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml
   --config sim/presets/panel-vary.toml)
for k in 0 1; do
    .venv/bin/station render --out data/warp-val-1199 "${P[@]}" --config $D/warp.toml --count 300 --seed 1199 \
        --defects 0.6 --validation --shard $k/2 > "runs/moulding-kinds/render-val-$k.log" 2>&1 &
done
wait
