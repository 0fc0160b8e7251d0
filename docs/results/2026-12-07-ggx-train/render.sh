#!/usr/bin/env bash
# The GGX training set: make model's training render (scripts/make-model.sh step 1) with ggx.toml layered last, its
# Beckmann parts linked from data/line-ef-train-900 (link.py) once its first part has made the set's manifest (station
# render takes no folder without one); then two shards, each waited on; run from the repository's root.
set -euo pipefail
export OMP_NUM_THREADS=1
HERE=docs/results/2026-12-07-ggx-train
OUT=data/line-ef-train-900-ggx
render() {  # render SHARD
    .venv/bin/station render --out "$OUT" --config sim/presets/line-polar.toml --config sim/presets/variation.toml \
        --config sim/presets/panel.toml --config sim/presets/panel-vary.toml --config sim/presets/finish-vary.toml \
        --config "$HERE/ggx.toml" --edge-mm 0,0.4 --count 900 --seed 101 --defects 0.4 --defects-in-train \
        --shard "$1"
}
render 0/900  # index 0 alone: the manifest
.venv/bin/python "$HERE/link.py" data/line-ef-train-900 "$OUT" 0.3
render 0/2 & a=$!
render 1/2 & b=$!
wait "$a"
wait "$b"
