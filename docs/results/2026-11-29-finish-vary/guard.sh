#!/bin/bash
# After rule 63 (from anywhere; resumable): the shipped file through rule 60's guards, on the sets they used: the
# panel at half its radiance (seed 1154), the lens blur alone (seed 1157) and all five camera imperfections (seed
# 1159), both with the fireflies brought to full scale, each beside the same parts as rendered. Then:
#   python guard.py runs/r63
set -euo pipefail
cd "$(dirname "$0")/../../.."  # the repository root
R=runs/r63
export PYTHONPATH=. OMP_NUM_THREADS=1
ev() { [ -f $R/eval-guard-$1/eval.md ] || .venv/bin/station eval --model model/weights/default --data data/$1 \
  --val-data data/line-pv-val --no-synthetic --no-plots --out $R/eval-guard-$1 > $R/eval-guard-$1.log 2>&1; }
(ev pb-half-1154; ev so-blurff-1157; ev so-allff-1159) &
ev line-panel-heldout-1154; ev line-panel-heldout-1157; ev line-panel-heldout-1159
wait
