#!/usr/bin/env bash
# Check 74 (check-74-plan.md): RL (the ramp with the whole recipe) against the shipped file on seed 1178, each on its
# own line's held-out set and thresholded on its own validation set. Resumable: each step skips what it has written.
# Needs render-1178.sh's two sets and the ramp's sets (render.sh) and Rv (screen.sh).
set -euo pipefail
D=docs/results/2026-12-01-ramp-panel
R=runs/c74
mkdir -p $R
[ -f $R/RL.pt ] || .venv/bin/station residual --model runs/s74/Rv --data data/ramp-pf-train \
  --val-data data/ramp-pf-val --members 1 --steps 3000 --second-look --out $R/RL > $R/RL.log 2>&1
[ -f $R/RL-threshold.log ] || .venv/bin/station threshold --model $R/RL --data data/ramp-pv-val \
  > $R/RL-threshold.log 2>&1
[ -f $R/eval-shipped-1178/scores.csv ] || .venv/bin/station eval --model model/weights/default \
  --data data/line-panel-heldout-1178 --val-data data/line-pv-val --no-synthetic --no-plots \
  --out $R/eval-shipped-1178 > $R/eval-shipped-1178.log 2>&1
[ -f $R/eval-RL-1178/scores.csv ] || .venv/bin/station eval --model $R/RL \
  --data data/ramp-heldout-1178 --val-data data/ramp-pv-val --no-synthetic --no-plots \
  --out $R/eval-RL-1178 > $R/eval-RL-1178.log 2>&1
.venv/bin/python $D/read_check.py data/line-panel-heldout-1178 $R/eval-shipped-1178 \
  data/ramp-heldout-1178 $R/eval-RL-1178 > $D/check-74.md
