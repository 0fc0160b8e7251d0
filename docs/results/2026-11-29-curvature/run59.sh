#!/bin/bash
# Rule 59 (rule59.md), from the repository root; resumable. Needs seed 1160 rendered (render1160.sh) and K made
# (candidate.sh). The amendment chose K1 by the validation lines (K1 69.6 %, K2 68.7 %; C 68.7 %).
set -euo pipefail
S=docs/results/2026-11-29-curvature
R=runs/r59
export PYTHONPATH=. OMP_NUM_THREADS=1
ev() { [ -f $R/eval-$1/eval.md ] || .venv/bin/station eval --model $2 --data data/$3 --val-data data/line-pv-val \
  ${4:-} --out $R/eval-$1 > $R/eval-$1.log 2>&1; }
(ev K1-1160 $R/K1 line-panel-heldout-1160; ev K1-half $R/K1 pb-half-1154 --no-synthetic) &
(ev C-1160 model/weights/default line-panel-heldout-1160; ev K1-all $R/K1 so-all-1159 --no-synthetic) &
wait
.venv/bin/python $S/decide59.py $R/eval-K1-1160 $R/eval-C-1160 $R/eval-K1-half $R/eval-K1-all $R/K1 | tee $S/decide59.md
