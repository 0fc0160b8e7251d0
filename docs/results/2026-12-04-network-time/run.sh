#!/usr/bin/env bash
# make model's networks (steps 3-5: base, mixed, band), the recipe's commands as scripts/make-model.sh runs them
# (on TRAIN_THREADS = 2 threads, nothing beside them), timed, on the training set make model renders (seed 101,
# 900 parts; its train and val splits, index % 10 in 2..9, rendered by ../2026-12-03-recipe-time/run.sh: the
# networks read no other split). Each command's wall seconds go to runs/network-time/timings.tsv; an interrupted run
# resumes from its last checkpoint when run again (a rerun's seconds add a line). Run from the repository root.
set -euo pipefail
BIN=.venv/bin
R=runs/network-time
DATA=data/line-ef-train
mkdir -p "$R"
export OMP_NUM_THREADS=2
MODEL=(--priors intensity,dolp,aolp --preset fast --fusion fused --batch-size 8 --seed 0 --device cpu)
timed() {  # timed NAME CMD...: run CMD, then append NAME, its wall seconds and the time to the timings
    local name=$1 t0=$SECONDS; shift
    "$@"
    printf '%s\t%s\t%s\n' "$name" "$((SECONDS - t0))" "$(date -Is)" >> "$R/timings.tsv"
}
timed base "$BIN/station" train --data "$DATA" "${MODEL[@]}" --steps 1000 --stop-at-step 500 --eval-every 100 \
    --out "$R/base"
timed mixed "$BIN/station" train --data "$DATA" "${MODEL[@]}" --steps 400 --eval-every 100 \
    --rendered-fraction 0.25 --init "$R/base/last" --out "$R/mixed"
timed band "$BIN/station" train --data "$DATA" "${MODEL[@]}" --roi band --size 96 --steps 1200 --eval-every 200 \
    --rendered-fraction 0.25 --init "$R/mixed/best" --out "$R/band"
