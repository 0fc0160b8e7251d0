#!/bin/bash
# stop 58 screen: where the panel-varied fit loses dents; variation + second look (no residual network), clusters 8 vs 0
cd /work/main
export OMP_NUM_THREADS=1
K=runs/s58/k
fit() { [ -f $K/$1.json ] || .venv/bin/station variation --model runs/r52/F/default --refit --data data/$2-train \
  --val-data data/$2-val --decision variation --clusters 0 --out $K/$1 > $K/$1.log 2>&1; }
fit X0k0 line-pv & fit C0k0 line-panel & wait
ev() { [ -f $K/eval-$1/eval.md ] || .venv/bin/station eval --model $2 --data data/line-panel-heldout-1155 \
  --val-data data/$3-val --no-synthetic --no-plots --out $K/eval-$1 > $K/eval-$1.log 2>&1; }
(ev X0 runs/r52/X0 line-pv; ev X0k0 $K/X0k0 line-pv) & (ev C0 runs/ship47/default line-panel; ev C0k0 $K/C0k0 line-panel) & wait
echo done > $K/done
