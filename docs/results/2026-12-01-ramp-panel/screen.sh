#!/usr/bin/env bash
# The ramp screen after render.sh (plan.md): Rv fitted as stop 73's reproduction Fv was, both scored on their own
# line's validation set, read paired. Fit ~6 min, scores ~3 min each.
set -euo pipefail
D=docs/results/2026-12-01-ramp-panel
R=${R:-runs/s74}
export OMP_NUM_THREADS=${OMP_NUM_THREADS:-2}
[ -f "$R/Rv.json" ] || .venv/bin/station variation --model runs/c73/repro/src/default --refit \
    --data data/ramp-pf-train --val-data data/ramp-pf-val --decision variation --out "$R/Rv"
.venv/bin/station eval --model runs/c73/repro/Fv --data data/line-pv-val --split val --no-synthetic --no-plots \
    --out $D/eval-Fv
.venv/bin/station eval --model "$R/Rv" --data data/ramp-pv-val --split val --no-synthetic --no-plots --out $D/eval-Rv
.venv/bin/python $D/read.py data/line-pv-val $D/eval-Fv/scores.csv data/ramp-pv-val $D/eval-Rv/scores.csv > $D/read.md
