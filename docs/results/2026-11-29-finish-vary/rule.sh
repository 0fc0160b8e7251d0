#!/bin/bash
# Rule 62 on seed 1164 (plan.md), run once the screen has passed; from anywhere; resumable. K3 (the shipped file)
# and F on S, G and R, each with thresholds from its own validation set. Then:
#   python decide62.py runs/r62/eval-K3-{}64 runs/r62/eval-F-{}64
set -euo pipefail
cd "$(dirname "$0")/../../.."  # the repository root
R=runs/r62
export PYTHONPATH=. OMP_NUM_THREADS=1
while [ ! -f $R/om-rough-1164.done ]; do sleep 20; done
ev() { [ -f $R/eval-$1/eval.md ] || .venv/bin/station eval --model $2 --data data/$3 --val-data data/$4 \
  --no-synthetic --no-plots --out $R/eval-$1 > $R/eval-$1.log 2>&1; }
(ev K3-S64 model/weights/default line-panel-heldout-1164 line-pv-val
 ev K3-G64 model/weights/default om-ggx-1164 line-pv-val
 ev K3-R64 model/weights/default om-rough-1164 line-pv-val) &
ev F-S64 $R/F line-panel-heldout-1164 line-pf-val
ev F-G64 $R/F om-ggx-1164 line-pf-val
ev F-R64 $R/F om-rough-1164 line-pf-val
wait
