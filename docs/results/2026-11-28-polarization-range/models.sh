#!/bin/sh
# Rule 38, after render.sh (run from the repository root; each step is skipped when its output exists): C fitted from
# the shipped model (A is rule 37's runs/gp/A, made by its models.sh), both evaluated on seed 1136 unshifted and
# shifted, C on rules 35-36's sets G, E, R; then the paired comparisons. `models.sh A` or `models.sh C` runs one
# model's evaluations only (the two can run side by side, one per core); without an argument, both, then the
# comparisons.
set -e
S=.venv/bin/station
D=docs/results/2026-11-28-polarization-range
G=docs/results/2026-11-28-global-polarization
mkdir -p runs/r38
[ -f runs/r38/C.json ] || $S variation --model model/weights/default --refit --data data/line-panel-train \
    --val-data data/line-panel-val --decision variation --global-polarization range --out runs/r38/C
model() { [ "$1" = A ] && echo runs/gp/A || echo runs/r38/C; }
for m in ${1:-A C}; do
    [ -f $D/eval-$m-1136/eval.json ] || $S eval --model $(model $m) --data data/line-panel-heldout-1136 \
        --val-data data/line-panel-val --out $D/eval-$m-1136
    [ -f $D/shift-$m/shift.json ] || $S bench shift --model $(model $m) --data data/line-panel-heldout-1136 \
        --val-data data/line-panel-val --shifts "none,dolp x0.5,dolp x2,aolp +5 deg" --out $D/shift-$m
    [ $m = A ] && continue
    for x in G:om-ggx E:om-ior R:om-rough; do
        set=${x%%:*}; data=${x#*:}
        [ -f $D/eval-C-$set/eval.json ] || $S eval --model runs/r38/C --data data/$data \
            --val-data data/line-panel-val --no-synthetic --no-plots --out $D/eval-C-$set
    done
done
[ -n "$1" ] && exit 0
$S compare --paired $D/eval-A-1136 $D/eval-C-1136 --out $D/paired-1136
for set in G E R; do $S compare --paired $G/eval-A-$set $D/eval-C-$set --out $D/paired-$set; done
