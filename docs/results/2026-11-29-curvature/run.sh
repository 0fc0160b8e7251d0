#!/bin/bash
# Rules 59 and 60 (rule59.md, rule60.md), from the repository root; resumable. `run.sh K1 1160 decide59.md` is
# rule 59 as amended (K1 chosen by the validation lines), `run.sh K3 1161 decide60.md` rule 60 (K3 past its
# validation gate). Needs the seed rendered (render.sh) and the candidate made (candidate.sh, candidate3.sh).
set -euo pipefail
K=$1 SEED=$2 OUT=$3
S=docs/results/2026-11-29-curvature
R=runs/r59
export PYTHONPATH=. OMP_NUM_THREADS=1
ev() { [ -f $R/eval-$1/eval.md ] || .venv/bin/station eval --model $2 --data data/$3 --val-data data/line-pv-val \
  ${4:-} --out $R/eval-$1 > $R/eval-$1.log 2>&1; }
(ev $K-$SEED $R/$K line-panel-heldout-$SEED; ev $K-half $R/$K pb-half-1154 --no-synthetic) &
(ev C-$SEED model/weights/default line-panel-heldout-$SEED; ev $K-all $R/$K so-all-1159 --no-synthetic) &
wait
.venv/bin/python $S/decide59.py $R/eval-$K-$SEED $R/eval-C-$SEED $R/eval-$K-half $R/eval-$K-all $R/$K | tee $S/$OUT
