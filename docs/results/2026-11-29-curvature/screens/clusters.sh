#!/bin/bash
# stop 59 screens: clusters without the panel direction (oracle), 16 clusters; no residual network; seed 1155 (used)
cd /work/main
export OMP_NUM_THREADS=1
S=runs/s59
fit() { [ -f $S/$1.json ] || .venv/bin/python $S/screen.py $2 runs/r52/F/default data/$3-train data/$3-val $S/$1 > $S/$1.log 2>&1; }
ev() { [ -f $S/eval-$1/eval.md ] || .venv/bin/station eval --model $S/$1 --data data/line-panel-heldout-1155 \
  --val-data data/$2-val --no-synthetic --no-plots --out $S/eval-$1 > $S/eval-$1.log 2>&1; }
(fit Xring ring line-pv; ev Xring line-pv) & (fit X16 k16 line-pv; ev X16 line-pv) & wait
(fit C16 k16 line-panel; ev C16 line-panel) & wait
echo done > $S/done
