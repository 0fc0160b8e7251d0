#!/bin/bash
# stop 59: the shipped file's look network trained without each defect type (held-out types), from rule 60's fit
# (runs/r59/K3v), as the shipped network was made; then each scored on the report set, seed 1162. Resumable.
cd /work/main
export OMP_NUM_THREADS=1
H=runs/h59
worker() {
  for t in "$@"; do
    [ -f $H/H-$t.json ] || .venv/bin/station residual --model runs/r59/K3v --data data/line-pv-train \
      --val-data data/line-pv-val --members 1 --steps 3000 --second-look --holdout-type $t --out $H/H-$t \
      > $H/H-$t.log 2>&1
    [ -f $H/eval-H-$t/eval.md ] || .venv/bin/station eval --model $H/H-$t --data data/line-panel-heldout-1162 \
      --val-data data/line-pv-val --no-synthetic --no-plots --out $H/eval-H-$t > $H/eval-H-$t.log 2>&1
  done
}
worker dent scratch stain & worker chip missing_stud & wait
echo done > $H/nets.done
