#!/usr/bin/env bash
# plan.md: make side-model beside the intensity-only line file, and the two-camera station on seeds 1196 and 1197.
# Run from anywhere; resumable (renders resume per sample; make side-model resumes; a finished report is kept).
# STEP=render|pair|all (default).
set -euo pipefail
HERE=$(cd "$(dirname "$0")" && pwd)
cd "$HERE/../../.."
BIN=.venv/bin
R=runs/two-cameras-intensity
mkdir -p "$R" "$HERE/eval"
export OMP_NUM_THREADS=1
STEP=${STEP:-all}
P=(--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml
   --count 400 --defects 0.6 --heldout)
SIDE=(--config sim/presets/side-view.toml)  # last: the side camera and its flat dome
render() {  # render SET SEED ARGS...: one process, resumable
    local set=$1 seed=$2; shift 2
    "$BIN/station" render --out "data/$set" "${P[@]}" --seed "$seed" "$@" > "$R/render-$set.log" 2>&1
}
if [ "$STEP" = render ] || [ "$STEP" = all ]; then
    render sw-heldout-1196 1196 "${SIDE[@]}" &
    render line-heldout-1197 1197 &
    render sw-heldout-1197 1197 "${SIDE[@]}" &
    wait
fi
judge() {  # judge CAMERA SET TAG: the camera's file on data/SET, thresholds from its validation set, into eval/
    local out="$HERE/eval/$1-$3"
    [ -f "$out/scores.csv" ] && return
    if [ "$1" = line ]; then
        "$BIN/station" eval --model model/weights/default --data "data/$2" --val-data data/line-pv-val \
            --no-synthetic --no-plots --out "$out" > "$R/eval-$1-$3.log" 2>&1
    else
        "$BIN/station" eval --model runs/make-side-model/side --data "data/$2" --val-data data/sw-pv-val \
            --presence-rule row_contrast --no-synthetic --no-plots --out "$out" > "$R/eval-$1-$3.log" 2>&1
    fi
}
if [ "$STEP" = pair ] || [ "$STEP" = all ]; then
    [ -f runs/make-side-model/split.json ]  # make side-model has finished
    cp runs/make-side-model/split.json "$HERE/split.json"
    sha256sum runs/make-side-model/side.pt > "$HERE/side.sha256"
    mkdir -p "$HERE/eval/line-1196"  # S on seed 1196, read by the ship-otherwise study
    cp "$HERE/../2026-12-04-ship-otherwise/eval/S-built/"{scores.csv,eval.json,eval.md} "$HERE/eval/line-1196/"
    judge side sw-heldout-1196 1196 &
    judge line line-heldout-1197 1197
    wait
    judge side sw-heldout-1197 1197
    for seed in 1196 1197; do
        "$BIN/station" compare "$HERE/eval/line-$seed" "$HERE/eval/side-$seed" --split "$HERE/split.json" \
            --out "$R/two-cameras-$seed" > "$R/compare-$seed.log" 2>&1
        for x in md json; do cp "$R/two-cameras-$seed/two-cameras.$x" "$HERE/two-cameras-$seed.$x"; done
    done
fi
