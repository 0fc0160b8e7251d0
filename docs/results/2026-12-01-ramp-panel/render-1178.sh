#!/usr/bin/env bash
# Check 74's held-out set (check-74-plan.md): seed 1178, 400 parts as make model renders its held-out set, on the
# line as built and with the ramp (the same parts). Resumable; about 20 min on 2 cores.
set -euo pipefail
D=docs/results/2026-12-01-ramp-panel
export OMP_NUM_THREADS=1
P=(--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml)
for set in line-panel-heldout-1178: ramp-heldout-1178:"--config $D/ramp.toml"; do
    name=${set%%:*}; extra=${set#*:}
    for k in 0 1; do
        # shellcheck disable=SC2086
        .venv/bin/station render --out data/$name "${P[@]}" $extra --count 400 --seed 1178 --defects 0.6 --heldout \
            --visibility --shard $k/2 &
    done
    wait
done
