#!/usr/bin/env bash
# A validation set of the new kinds (screen.md): seed 1180, 400 parts rendered as make model renders its VAL set
# (the line, the panel drawn per part; every sample val), blisters and debris only. For choosing a window that also
# sees small defects without reading seed 1179. Resumable; about 12 min on 2 cores.
set -euo pipefail
D=docs/results/2026-12-01-new-kinds
export OMP_NUM_THREADS=1
P=(--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml
   --config sim/presets/panel-vary.toml)
for k in 0 1; do
    .venv/bin/station render --out data/new-kinds-val-1180 "${P[@]}" --config $D/types.toml --count 400 --seed 1180 \
        --defects 0.6 --validation --shard $k/2 &
done
wait
