#!/bin/bash
# rule 59's candidate K: the shipped recipe with the curvature window (sigma 3), from rule 52's networks (runs/r52/F),
# as runs/r52/X0 and X were made (station variation --refit, then the look's residual network)
cd /work/main
export OMP_NUM_THREADS=1
R=runs/r59
[ -f $R/K0.json ] || .venv/bin/station variation --model runs/r52/F/default --refit --data data/line-pv-train \
  --val-data data/line-pv-val --decision variation --curvature 3 --out $R/K0 > $R/K0.log 2>&1
[ -f $R/K.json ] || .venv/bin/station residual --model $R/K0 --data data/line-pv-train --val-data data/line-pv-val \
  --members 1 --steps 3000 --second-look --out $R/K > $R/K.log 2>&1
echo done > $R/candidate.done
# amendment: K1, the curvature window without the second look (and so without its network)
[ -f $R/K1.json ] || .venv/bin/station variation --model runs/r52/F/default --refit --data data/line-pv-train \
  --val-data data/line-pv-val --decision variation --curvature 3 --no-second-look --out $R/K1 > $R/K1.log 2>&1
echo done > $R/candidate1.done
