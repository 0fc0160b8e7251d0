#!/usr/bin/env bash
# plan.md: IN-G (intensity + the renderer's normals) joined with RAD (runs/c76/V1) at rule 64's split, validation only.
set -euo pipefail
cd "$(dirname "$0")/../../../.."  # the repository root
D=docs/results/2026-12-01-normal-prior/joined
R=runs/c77
export OMP_NUM_THREADS=2
NET=(--preset fast --fusion fused --batch-size 8 --seed 0 --device cpu --roi band --size 96 --steps 2 --eval-every 2)
[ -f $R/ING-net/best.json ] || .venv/bin/station train --data data/line-pf-train --priors intensity,normal \
    "${NET[@]}" --out $R/ING-net > $R/ING-net.log 2>&1
[ -f $R/ING.json ] || .venv/bin/station variation --model $R/ING-net/best --data data/line-pf-train \
    --val-data data/line-pf-val --curvature 3 --out $R/ING > $R/ING-fit.log 2>&1
for m in c76/V1 c77/ING; do
    e=$R/eval-1176-$(basename $m)
    [ -f $e/scores.csv ] || .venv/bin/station eval --model runs/$m --data data/line-pv-val-1176 --split val \
        --val-data data/line-pv-val --no-synthetic --no-plots --out $e > $e.log 2>&1
done
[ -f $R/split-ING.json ] || .venv/bin/station split --model runs/c76/V1 --data data/line-pv-val \
    --second-model $R/ING --second-data data/line-pv-val --second-presence-rule dolp_contrast \
    --out $R/split-ING.json > $R/split-ING.log 2>&1
.venv/bin/station compare $R/eval-1176-V1 $R/eval-1176-ING --split $R/split-ING.json --out $R/pair-ING
mkdir -p $D
cp $R/pair-ING/* $R/split-ING.json $D/
for m in V1 ING; do cp $R/eval-1176-$m/eval.md $D/eval-1176-$m.md; done
# the reading against RAD alone at the line's 1 % (read.md), by the join reader the later tilt studies share
.venv/bin/python docs/results/2026-12-01-tilt-apart/read.py $R/eval-1176-V1 "IN-G=$R/eval-1176-ING:$R/split-ING.json" \
    > $D/read.md
