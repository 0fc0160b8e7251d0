#!/bin/bash
# Halo screen (from the repository root; resumable): the shipped file with the highlight mask grown by 5 (as
# shipped), 8 and 11 input px, on the validation set (selection) and on check 61's G and R sets (used).
set -euo pipefail
R=runs/halo
mkdir -p $R
export PYTHONPATH=. OMP_NUM_THREADS=1
ev() { [ -f $R/eval-$1-$2/eval.md ] || .venv/bin/python docs/results/2026-11-29-other-means-curvature/halo/grow.py \
  $1 --model model/weights/default --data data/$3 ${4:-} --val-data data/line-pv-val --no-synthetic --no-plots \
  --out $R/eval-$1-$2 > $R/eval-$1-$2.log 2>&1; }
(ev 5 val line-pv-val "--split val"; ev 8 val line-pv-val "--split val"; ev 11 val line-pv-val "--split val") &
(ev 8 R om-rough-1163; ev 11 R om-rough-1163; ev 8 G om-ggx-1163; ev 11 G om-ggx-1163) &
wait
