#!/usr/bin/env bash
# plan.md's sets F, V and T. Resumable, two shards each; run from the repository's root.
set -euo pipefail
export OMP_NUM_THREADS=1
P=(--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml)
TRAINING=(--config sim/presets/panel-vary.toml --config sim/presets/finish-vary.toml --edge-mm 0,0.4)
render() {  # render OUT ARGS...
    local out=$1; shift
    for k in 0 1; do
        .venv/bin/station render --out "$out" "${P[@]}" "$@" --shard "$k/2" &
    done
    wait
}
render data/fit-1213 "${TRAINING[@]}" --count 1100 --seed 1213 --defects 0.4
render data/fit-1215-val "${TRAINING[@]}" --count 400 --seed 1215 --defects 0.4 --validation
render data/fit-1214-test --count 400 --seed 1214 --defects 0.6 --heldout
