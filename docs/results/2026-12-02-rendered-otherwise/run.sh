#!/bin/bash
# Plan 68 (plan.md), from anywhere; resumable (a finished report is skipped). After render.sh: the shipped file E63
# on every set, then the file before F63 (runs/r68/F63, 52b97c7's model/weights/default), two lanes, one per core.
# Then: python table.py runs/r68 > table.md
set -euo pipefail
cd "$(dirname "$0")/../../.."  # the repository root
R=runs/r68
export PYTHONPATH=. OMP_NUM_THREADS=1
while [ ! -f $R/render.done ]; do sleep 30; done
ev() {  # file name, model, set
  [ -f $R/eval-$1-$3/eval.md ] || .venv/bin/station eval --model $2 --data data/$3 --no-synthetic --no-plots \
    --out $R/eval-$1-$3 > $R/eval-$1-$3.log 2>&1
}
E=model/weights/default
F=$R/F63/default
(ev E63 $E line-panel-heldout-1188; ev E63 $E om-ggx-1188; ev E63 $E om-rough-1188
 ev F63 $F line-panel-heldout-1188; ev F63 $F om-ggx-1188; ev F63 $F om-rough-1188) &
ev E63 $E pb-half-1188; ev E63 $E so-blurff-1188; ev E63 $E so-allff-1188
ev F63 $F pb-half-1188; ev F63 $F so-blurff-1188; ev F63 $F so-allff-1188
wait
touch $R/run.done
