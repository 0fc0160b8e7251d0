#!/bin/bash
# Rule 60 (rule60.md), from the repository root; resumable. Needs seed 1161 rendered and K3 made (candidate3.sh),
# and K3 past the validation gate.
set -euo pipefail
S=docs/results/2026-11-29-curvature
R=runs/r59
export PYTHONPATH=. OMP_NUM_THREADS=1
ev() { [ -f $R/eval-$1/eval.md ] || .venv/bin/station eval --model $2 --data data/$3 --val-data data/line-pv-val \
  ${4:-} --out $R/eval-$1 > $R/eval-$1.log 2>&1; }
(ev K3-1161 $R/K3 line-panel-heldout-1161; ev K3-half $R/K3 pb-half-1154 --no-synthetic) &
(ev C-1161 model/weights/default line-panel-heldout-1161; ev K3-all $R/K3 so-all-1159 --no-synthetic) &
wait
.venv/bin/python $S/decide59.py $R/eval-K3-1161 $R/eval-C-1161 $R/eval-K3-half $R/eval-K3-all $R/K3 | tee $S/decide60.md
