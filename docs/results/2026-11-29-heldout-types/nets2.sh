#!/bin/bash
# stop 58: nets.sh again after two networks died at their end (the code they import was being edited); two workers,
# each first waits for the network already training in its slot; resumable
cd /work/main
export OMP_NUM_THREADS=1
worker() {
  for t in "$@"; do
    while pgrep -f -- "--holdout-type $t " > /dev/null; do sleep 30; done
    [ -f runs/h58/H-$t.json ] && continue
    .venv/bin/station residual --model runs/r52/X0 --data data/line-pv-train --val-data data/line-pv-val \
      --members 1 --steps 3000 --second-look --holdout-type $t --out runs/h58/H-$t > runs/h58/H-$t.log 2>&1
  done
}
worker scratch dent chip & worker missing_stud stain & wait
echo done > runs/h58/nets.done
