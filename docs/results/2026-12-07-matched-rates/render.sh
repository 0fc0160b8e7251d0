#!/usr/bin/env bash
# plan.md's fresh sets, one after another, each resumable in two shards; run from the repository's root.
set -euo pipefail
export OMP_NUM_THREADS=1
LINE=(--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml)
render() {  # render OUT SEED COUNT [ARGS]: two shards, each waited on (a failed shard stops the script)
    local pids=()
    for k in 0 1; do
        .venv/bin/station render --out "$1" "${LINE[@]}" "${@:4}" --count "$3" --seed "$2" --defects 0.4 --heldout \
            --shard "$k/2" & pids+=($!)
    done
    for p in "${pids[@]}"; do wait "$p"; done
}
render data/square-1236 1236 600
render data/turned20-1237 1237 400 --config docs/results/2026-12-06-turns/turned20.toml
