#!/bin/bash
# Check 61's addendum (plan.md), from the repository root, after run.sh; resumable.
set -euo pipefail
R=runs/c61
export PYTHONPATH=. OMP_NUM_THREADS=1
while pgrep -f "other-means-curvature/run.sh" > /dev/null; do sleep 20; done
[ -f $R/A.pt ] || .venv/bin/station adapt --model model/weights/default --good data/line-panel-val --split val \
  --out $R/A > $R/adapt.log 2>&1
ev() { [ -f $R/eval-$1/eval.md ] || .venv/bin/station eval --model $R/A --data data/$2 --no-synthetic --no-plots \
  --out $R/eval-$1 > $R/eval-$1.log 2>&1; }
(ev A-S line-panel-heldout-1163; ev A-R om-rough-1163) &
ev A-G om-ggx-1163
wait
