#!/bin/bash
# stop 58: each held-out-type network's station eval on seed 1159 (after nets.sh); resumable
cd /work/main
export OMP_NUM_THREADS=1
# each evaluation starts when its network is written
ev() { for t in "$@"; do
  while [ ! -f runs/h58/H-$t.json ]; do sleep 30; done
  [ -f runs/h58/eval-H-$t/eval.md ] || .venv/bin/station eval --model runs/h58/H-$t --data data/line-panel-heldout-1159 \
     --val-data data/line-pv-val --no-synthetic --out runs/h58/eval-H-$t > runs/h58/eval-H-$t.log 2>&1
done; }
ev scratch dent chip & ev missing_stud stain & wait
echo done > runs/h58/evals.done
