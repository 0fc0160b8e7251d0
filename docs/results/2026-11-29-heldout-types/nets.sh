#!/bin/bash
# stop 58: the shipped file's residual network trained without each defect type (as stop 55 for the file before);
# two workers; resumable (a finished network has its .json)
cd /work/main
export OMP_NUM_THREADS=1
worker() {
  for t in "$@"; do
    [ -f runs/h58/H-$t.json ] && continue
    .venv/bin/station residual --model runs/r52/X0 --data data/line-pv-train --val-data data/line-pv-val \
      --members 1 --steps 3000 --second-look --holdout-type $t --out runs/h58/H-$t > runs/h58/H-$t.log 2>&1
  done
}
worker dent scratch chip & worker stain missing_stud & wait
echo done > runs/h58/nets.done
