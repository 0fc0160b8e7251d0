#!/usr/bin/env bash
# plan.md: IN-G's recipe on normals carrying a 1- and a 3-degree error, each joined with RAD (runs/c76/V1) at rule
# 64's split; validation only. Resumable (degrade.py skips made samples; each later step skips a finished output).
# Per level: about 5 GB of copies (gt.npz only) and 15 min to make them, the fit and the evaluations.
set -euo pipefail
cd "$(dirname "$0")/../../.."  # the repository root
D=docs/results/2026-12-01-normal-precision
R=runs/c78
mkdir -p $R
export OMP_NUM_THREADS=2 PYTHONPATH=.
NET=(--preset fast --fusion fused --batch-size 8 --seed 0 --device cpu --roi band --size 96 --steps 2 --eval-every 2)
pairs=()
for L in ${LEVELS:-3 1}; do
    for s in line-pf-train line-pf-val line-pv-val line-pv-val-1176; do
        [ -f data/np$L-${s#line-}/done ] || { .venv/bin/python $D/degrade.py $L data/$s data/np$L-${s#line-} \
            > $R/degrade-$L-$s.log && touch data/np$L-${s#line-}/done; }
    done
    [ -f $R/IN$L-net/best.json ] || .venv/bin/station train --data data/np$L-pf-train --priors intensity,normal \
        "${NET[@]}" --out $R/IN$L-net > $R/IN$L-net.log 2>&1
    [ -f $R/IN$L.json ] || .venv/bin/station variation --model $R/IN$L-net/best --data data/np$L-pf-train \
        --val-data data/np$L-pf-val --curvature 3 --out $R/IN$L > $R/IN$L-fit.log 2>&1
    e=$R/eval-1176-IN$L
    [ -f $e/scores.csv ] || .venv/bin/station eval --model $R/IN$L --data data/np$L-pv-val-1176 --split val \
        --val-data data/np$L-pv-val --no-synthetic --no-plots --out $e > $e.log 2>&1
    [ -f $R/split-IN$L.json ] || .venv/bin/station split --model runs/c76/V1 --data data/line-pv-val \
        --second-model $R/IN$L --second-data data/np$L-pv-val --second-presence-rule dolp_contrast \
        --out $R/split-IN$L.json > $R/split-IN$L.log 2>&1
    pairs+=("IN-$L=$e:$R/split-IN$L.json")
    mkdir -p $D/eval
    cp $e/eval.md $D/eval/eval-1176-IN$L.md
    cp $R/split-IN$L.json $D/eval/
done
.venv/bin/python docs/results/2026-12-01-tilt-apart/read.py runs/c77/eval-1176-V1 "${pairs[@]}" \
    "IN-G=runs/c77/eval-1176-ING:runs/c77/split-ING.json" > $D/read.md
grep -h "median angular error" $R/degrade-*.log > $D/degrade.txt
