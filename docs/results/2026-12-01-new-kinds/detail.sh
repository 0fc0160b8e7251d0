#!/usr/bin/env bash
# detail.md: variation-only files at the shipped detail (V1) and at twice it (V2), screened on validation sets.
set -euo pipefail
D=docs/results/2026-12-01-new-kinds
R=runs/c76
NET=(--priors intensity,dolp,aolp --preset fast --fusion fused --batch-size 8 --seed 0 --device cpu --roi band
     --steps 2 --eval-every 2)
export OMP_NUM_THREADS=2
for v in "V1 96 3" "V2 192 6"; do
    set -- $v
    [ -f $R/$1-net/best.json ] || .venv/bin/station train --data data/line-pf-train "${NET[@]}" --size $2 \
        --out $R/$1-net > $R/$1-net.log 2>&1
    [ -f $R/$1.json ] || /usr/bin/time -v .venv/bin/station variation --model $R/$1-net/best --data data/line-pf-train \
        --val-data data/line-pf-val --curvature $3 --out $R/$1 > $R/$1-fit.log 2>&1
done
SIGMAS=1,1.5,2,3 .venv/bin/python $D/scale_screen.py $R/V1 data/line-pv-val $D/detail-V1.json \
    data/new-kinds-val-1180:val > $D/detail-V1.txt
SIGMAS=2,3,4,6 .venv/bin/python $D/scale_screen.py $R/V2 data/line-pv-val $D/detail-V2.json \
    data/new-kinds-val-1180:val > $D/detail-V2.txt
