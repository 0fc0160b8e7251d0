#!/usr/bin/env bash
# plan.md's fresh sets, one after another, each resumable in two shards (each waited on); then the read, each set
# once; run from the repository's root.
set -euo pipefail
export OMP_NUM_THREADS=1
LINE=(--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml)
render() {  # render OUT SEED COUNT [ARGS]
    local pids=()
    for k in 0 1; do
        .venv/bin/station render --out "$1" "${LINE[@]}" "${@:4}" --count "$3" --seed "$2" --defects 0.4 --heldout \
            --shard "$k/2" & pids+=($!)
    done
    for p in "${pids[@]}"; do wait "$p"; done
}
render data/square-1238 1238 600
render data/rough-1239 1239 400 --config docs/results/2026-11-28-other-means/rough.toml
for set in data/square-1238 data/rough-1239; do
    PYTHONPATH=. .venv/bin/python docs/results/2026-12-07-blend-rates/read.py "$set"
done
