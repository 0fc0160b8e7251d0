#!/usr/bin/env bash
# The recipe's own sets, as make-model.sh renders them (resumable): its training set (seed 101; only the splits the fit
# reads, index % 10 in 2..9, as docs/results/2026-12-03-recipe-time/run.sh renders it), its calibration set and its
# validation set (seed 303). The shipped file E63 was fitted on these parts; they are no evaluation set.
set -euo pipefail
cd "$(dirname "$0")/../../.."
BIN=.venv/bin
export OMP_NUM_THREADS=1
PRESET=(--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml)
VARY=(--config sim/presets/panel-vary.toml)
FINISH=(--config sim/presets/finish-vary.toml)
EDGES=(--edge-mm 0,0.4)
two() {  # two CMD...: CMD's shards k/2 on both cores
    local k pids=()
    for k in 0 1; do "$@" --shard "$k/2" & pids+=($!); done
    for k in "${pids[@]}"; do wait "$k"; done
}
for half in 0 1; do
    (for j in $((2 + half)) $((4 + half)) $((6 + half)) $((8 + half)); do
        "$BIN/station" render --out data/line-ef-train "${PRESET[@]}" "${VARY[@]}" "${FINISH[@]}" "${EDGES[@]}" \
            --count 900 --seed 101 --defects 0.4 --defects-in-train --shard "$j/10"
    done) & pids[half]=$!
done
wait "${pids[0]}"; wait "${pids[1]}"
two "$BIN/station" render --out data/line-ef-val "${PRESET[@]}" "${VARY[@]}" "${FINISH[@]}" "${EDGES[@]}" \
    --count 600 --seed 303 --defects 0.4 --validation
two "$BIN/station" render --out data/line-pv-val "${PRESET[@]}" "${VARY[@]}" --count 600 --seed 303 --defects 0.4 \
    --validation
