#!/usr/bin/env bash
# plan-2.md: the stripes' channels inside the line's file (RADF) against RAD (runs/c76/V1) on seed 1176; validation
# only. Needs run.sh's F sets. Resumable (each step skips a finished output).
set -euo pipefail
cd "$(dirname "$0")/../../.."  # the repository root
D=docs/results/2026-12-01-deflectometry
R=runs/c79
export OMP_NUM_THREADS=2 PYTHONPATH=.
NET=(--preset fast --fusion fused --batch-size 8 --seed 0 --device cpu --roi band --size 96 --steps 2 --eval-every 2)
[ -f $R/RADF-net/best.json ] || .venv/bin/station train --data data/fq-pf-train --priors intensity,dolp,aolp,normal \
    "${NET[@]}" --out $R/RADF-net > $R/RADF-net.log 2>&1
[ -f $R/RADF.json ] || .venv/bin/station variation --model $R/RADF-net/best --data data/fq-pf-train \
    --val-data data/fq-pv-val --curvature 3 --out $R/RADF > $R/RADF-fit.log 2>&1
e=$R/eval-1176-RADF
[ -f $e/scores.csv ] || .venv/bin/station eval --model $R/RADF --data data/fq-pv-val-1176 --split val \
    --val-data data/fq-pv-val --no-synthetic --no-plots --out $e > $e.log 2>&1
.venv/bin/station compare --paired runs/c77/eval-1176-V1 runs/c79/eval-1176-F $e --out $R/compare-RADF
mkdir -p $D/eval
cp $R/compare-RADF/* $D/eval/
cp $e/eval.md $D/eval/eval-1176-RADF.md
