#!/usr/bin/env bash
# polarization.md: V1 (detail.sh) against VI, the same variation-only fit on intensity alone; validation sets only.
set -euo pipefail
D=docs/results/2026-12-01-new-kinds
R=runs/c76
export OMP_NUM_THREADS=2
[ -f $R/VI-net/best.json ] || .venv/bin/station train --data data/line-pf-train --priors intensity --preset fast \
    --fusion fused --batch-size 8 --seed 0 --device cpu --roi band --size 96 --steps 2 --eval-every 2 \
    --out $R/VI-net > $R/VI-net.log 2>&1
[ -f $R/VI.json ] || .venv/bin/station variation --model $R/VI-net/best --data data/line-pf-train \
    --val-data data/line-pf-val --curvature 3 --out $R/VI > $R/VI-fit.log 2>&1
.venv/bin/python $D/scale_screen.py $R/VI data/line-pv-val $D/polarization-VI.json data/new-kinds-val-1180:val \
    > $D/polarization-VI.txt
# follow-up (polarization.md, "One line disagrees"): the same screen with the calibration set as VAL
for m in V1 VI; do
    .venv/bin/python $D/scale_screen.py $R/$m data/line-pf-val $D/polarization-$m-pfval.json \
        > $D/polarization-$m-pfval.txt
done
