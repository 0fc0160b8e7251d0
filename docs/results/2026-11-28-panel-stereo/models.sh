#!/bin/sh
# Rule 34, after render.sh (run from the repository root; each step is skipped when its output exists).
set -e
S=.venv/bin/station
D=docs/results/2026-11-28-panel-stereo
fit() {  # NAME PRIORS
    [ -f runs/pst/$1/last.json ] || $S train --data data/pst-train --priors $2 --preset fast --fusion fused \
        --roi band --size 96 --steps 30 --batch-size 8 --eval-every 30 --device cpu --seed 0 --out runs/pst/$1
    [ -f runs/pst/$1-v.json ] || $S variation --model runs/pst/$1/last --data data/pst-train \
        --val-data data/pst-val --out runs/pst/$1-v
    [ -f $D/eval-$1/eval.json ] || $S eval --model runs/pst/$1-v --data data/pst-heldout --val-data data/pst-val \
        --out $D/eval-$1
}
fit A intensity,dolp,aolp
fit C intensity,dolp,aolp,tilt_x
$S compare --paired $D/eval-A $D/eval-C --out $D/paired
