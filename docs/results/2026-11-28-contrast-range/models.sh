#!/bin/sh
# Rule 41 (run from the repository root; each step is skipped when its output exists): K fitted from the shipped model (C), both evaluated on seed 1140 unshifted and shifted, K on rules 35-36's sets
# G, E, R; then the paired comparisons. `models.sh C` or `models.sh K` runs one model's evaluations only.
set -e
S=.venv/bin/station
OUT=docs/results/2026-11-28-contrast-range
R=docs/results/2026-11-28-polarization-range
# seed 1140: station render --config sim/presets/line-polar.toml --config sim/presets/variation.toml
#   --config sim/presets/panel.toml --count 400 --seed 1140 --defects 0.6 --heldout
#   --out data/line-panel-heldout-1140 (--shard 0/2, then 1/2)
mkdir -p runs/r41
case "${1:-C K}" in *K*) [ -f runs/r41/K.json ] || $S variation --model model/weights/default --refit --data data/line-panel-train \
    --val-data data/line-panel-val --decision variation --contrast-range --out runs/r41/K;;
esac
SHIFTS="none,gamma 1.25,gamma 0.8,dolp x0.5,dolp x2,aolp +5 deg,blur 1 px,blur 0.5 px,rotate 5 deg,zoom x1.05"
model() { [ "$1" = C ] && echo model/weights/default || echo runs/r41/K; }
for m in ${1:-C K}; do
    [ -f $OUT/eval-$m-1140/eval.json ] || $S eval --model $(model $m) --data data/line-panel-heldout-1140 \
        --val-data data/line-panel-val --no-plots --out $OUT/eval-$m-1140
    [ -f $OUT/shift-$m/shift.json ] || $S bench shift --model $(model $m) --data data/line-panel-heldout-1140 \
        --val-data data/line-panel-val --shifts "$SHIFTS" --out $OUT/shift-$m
    [ $m = C ] && continue
    for x in G:om-ggx E:om-ior R:om-rough; do
        set=${x%%:*}; data=${x#*:}
        [ -f $OUT/eval-K-$set/eval.json ] || $S eval --model runs/r41/K --data data/$data \
            --val-data data/line-panel-val --no-synthetic --no-plots --out $OUT/eval-K-$set
    done
done
[ -n "$1" ] && exit 0
$S compare --paired $OUT/eval-C-1140 $OUT/eval-K-1140 --out $OUT/paired-1140
for set in G E R; do $S compare --paired $R/eval-C-$set $OUT/eval-K-$set --out $OUT/paired-$set; done
