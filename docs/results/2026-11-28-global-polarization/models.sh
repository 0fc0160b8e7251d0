#!/bin/sh
# Rule 37, after render.sh (run from the repository root; each step is skipped when its output exists): the control
# A and the candidate B fitted from the shipped model, evaluated on seed 1134 (unshifted and shifted) and on rules
# 35-36's sets S, G, E, R; then the paired comparisons. `models.sh A` or `models.sh B` runs one model's evaluations
# only (the two can run side by side, one per core); without an argument, both, then the comparisons.
set -e
S=.venv/bin/station
D=docs/results/2026-11-28-global-polarization
O=docs/results/2026-11-28-other-means
mkdir -p runs/gp
fit() {  # name, then extra arguments
    name=$1; shift
    [ -f runs/gp/$name.json ] || $S variation --model model/weights/default --refit --data data/line-panel-train \
        --val-data data/line-panel-val --decision variation --out runs/gp/$name "$@"
}
fit A --no-global-polarization
fit B --global-polarization
for m in ${1:-A B}; do
    [ -f $D/eval-$m-1134/eval.json ] || $S eval --model runs/gp/$m --data data/line-panel-heldout-1134 \
        --val-data data/line-panel-val --out $D/eval-$m-1134
    [ -f $D/shift-$m/shift.json ] || $S bench shift --model runs/gp/$m --data data/line-panel-heldout-1134 \
        --val-data data/line-panel-val --shifts "none,dolp x0.5,dolp x2,aolp +5 deg" --out $D/shift-$m
    for x in S:line-panel-heldout-1133 G:om-ggx E:om-ior R:om-rough; do
        set=${x%%:*}; data=${x#*:}
        [ -f $D/eval-$m-$set/eval.json ] || $S eval --model runs/gp/$m --data data/$data \
            --val-data data/line-panel-val --no-synthetic --no-plots --out $D/eval-$m-$set
    done
done
[ -n "$1" ] && exit 0
$S compare --paired $D/eval-A-1134 $D/eval-B-1134 --out $D/paired-1134
for set in S G E R; do $S compare --paired $D/eval-A-$set $D/eval-B-$set --out $D/paired-$set; done
