#!/usr/bin/env bash
# The ramp panel's twins of make model's training, calibration and validation sets (scripts/make-model.sh: the same
# seeds, counts and presets, ramp.toml layered last). Resumable; about 50 min on 2 cores.
set -euo pipefail
D=docs/results/2026-12-01-ramp-panel
export OMP_NUM_THREADS=1
PRESET=(--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml)
VARY=(--config sim/presets/panel-vary.toml)
FINISH=(--config sim/presets/finish-vary.toml)
RAMP=(--config $D/ramp.toml)
render() {  # render OUT ARGS...: two shards in parallel
    local out=$1; shift
    for k in 0 1; do .venv/bin/station render --out "$out" "${PRESET[@]}" --shard "$k/2" "$@" & done
    wait
}
render data/ramp-pv-val "${VARY[@]}" "${RAMP[@]}" --count 600 --seed 303 --defects 0.4 --validation
render data/ramp-pf-train "${VARY[@]}" "${FINISH[@]}" "${RAMP[@]}" --count 900 --seed 101 --defects 0.4 \
    --defects-in-train
render data/ramp-pf-val "${VARY[@]}" "${FINISH[@]}" "${RAMP[@]}" --count 600 --seed 303 --defects 0.4 --validation
