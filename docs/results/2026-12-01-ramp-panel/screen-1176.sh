#!/usr/bin/env bash
# The second reading (plan-2.md), after render-1176.sh and screen.sh: Fv and Rv (unchanged) on seed 1176's twins,
# read alone and pooled with seed 303's.
set -euo pipefail
D=docs/results/2026-12-01-ramp-panel
R=${R:-runs/s74}
export OMP_NUM_THREADS=${OMP_NUM_THREADS:-2}
.venv/bin/station eval --model runs/c73/repro/Fv --data data/line-pv-val-1176 --split val --no-synthetic \
    --no-plots --out $D/eval-Fv-1176
.venv/bin/station eval --model "$R/Rv" --data data/ramp-pv-val-1176 --split val --no-synthetic --no-plots \
    --out $D/eval-Rv-1176
.venv/bin/python $D/read.py data/line-pv-val-1176 $D/eval-Fv-1176/scores.csv data/ramp-pv-val-1176 \
    $D/eval-Rv-1176/scores.csv > $D/read-1176.md
.venv/bin/python $D/read.py data/line-pv-val $D/eval-Fv/scores.csv data/ramp-pv-val $D/eval-Rv/scores.csv \
    data/line-pv-val-1176 $D/eval-Fv-1176/scores.csv data/ramp-pv-val-1176 $D/eval-Rv-1176/scores.csv \
    > $D/read-pooled.md
