#!/bin/bash
# K3: the curvature window (sigma 3), the second look's gate without its test, and the look network asked above it
cd /work/main
export OMP_NUM_THREADS=1
R=runs/r59
[ -f $R/K3v.json ] || .venv/bin/station variation --model runs/r52/F/default --refit --data data/line-pv-train \
  --val-data data/line-pv-val --decision variation --curvature 3 --no-second-look-test --out $R/K3v > $R/K3v.log 2>&1
[ -f $R/K3.json ] || .venv/bin/station residual --model $R/K3v --data data/line-pv-train --val-data data/line-pv-val \
  --members 1 --steps 3000 --second-look --out $R/K3 > $R/K3.log 2>&1
echo done > $R/candidate3.done
