#!/bin/bash
# After rule 63 (from anywhere; resumable): the shipped file's look network trained without each defect type
# (held-out types), from rule 62's fit (runs/r62/Fv) as the shipped network was made, thresholded on the line as
# built as the shipped file was (station threshold on data/line-pv-val), then each scored on the report set, seed 1165.
# Its sets and fit: heldout/sets.sh. Arguments: the types (default all five), shared between two workers in turn.
set -euo pipefail
cd "$(dirname "$0")/../../../.."  # the repository root
export OMP_NUM_THREADS=1
H=runs/h63
mkdir -p $H
worker() {
  for t in "$@"; do
    if [ ! -f $H/H-$t.json ]; then
      .venv/bin/station residual --model runs/r62/Fv --data data/line-pf-train --val-data data/line-pf-val \
        --members 1 --steps 3000 --second-look --holdout-type $t --out $H/H-$t-cal > $H/H-$t.log 2>&1
      .venv/bin/station threshold --model $H/H-$t-cal --data data/line-pv-val >> $H/H-$t.log 2>&1
      .venv/bin/python -c "import sys; from model.draem.checkpoint import copy_checkpoint; copy_checkpoint(*sys.argv[1:])" \
        $H/H-$t-cal $H/H-$t
    fi
    [ -f $H/eval-H-$t/eval.md ] || .venv/bin/station eval --model $H/H-$t --data data/line-panel-heldout-1165 \
      --val-data data/line-pv-val --no-synthetic --no-plots --out $H/eval-H-$t > $H/eval-H-$t.log 2>&1
  done
}
types=(${@:-dent scratch stain chip missing_stud})
worker "${types[@]:0:1}" "${types[@]:2:1}" "${types[@]:4:1}" & worker "${types[@]:1:1}" "${types[@]:3:1}" & wait
echo done > $H/nets.done
