#!/bin/sh
# Rule 40 (run from the repository root; each step is skipped when its output exists): the held-out set of seed 1139,
# L fitted from the shipped model (C), both evaluated on seed 1139 unshifted and shifted, L on rules 35-36's sets
# G, E, R; then the paired comparisons. `models.sh C` or `models.sh L` runs one model's evaluations only.
set -e
S=.venv/bin/station
OUT=docs/results/2026-11-28-appearance-clusters
R=docs/results/2026-11-28-polarization-range
V="--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml"
mkdir -p runs/r40
[ -f runs/r40/render-1139.done ] || { for i in 0 1; do
    $S render $V --count 400 --seed 1139 --defects 0.6 --heldout --out data/line-panel-heldout-1139 --shard $i/2 &
    done; wait; touch runs/r40/render-1139.done; }
case "${1:-C L}" in *L*) [ -f runs/r40/L.json ] || $S variation --model model/weights/default --refit --data data/line-panel-train \
    --val-data data/line-panel-val --decision variation --clusters 8 --out runs/r40/L;;
esac
SHIFTS="none,blur 1 px,dolp x0.5,dolp x2,aolp +5 deg,gamma 1.25,blur 0.5 px,rotate 5 deg,zoom x1.05"
model() { [ "$1" = C ] && echo model/weights/default || echo runs/r40/L; }
for m in ${1:-C L}; do
    [ -f $OUT/eval-$m-1139/eval.json ] || $S eval --model $(model $m) --data data/line-panel-heldout-1139 \
        --val-data data/line-panel-val --no-plots --out $OUT/eval-$m-1139
    [ -f $OUT/shift-$m/shift.json ] || $S bench shift --model $(model $m) --data data/line-panel-heldout-1139 \
        --val-data data/line-panel-val --shifts "$SHIFTS" --out $OUT/shift-$m
    [ $m = C ] && continue
    for x in G:om-ggx E:om-ior R:om-rough; do
        set=${x%%:*}; data=${x#*:}
        [ -f $OUT/eval-L-$set/eval.json ] || $S eval --model runs/r40/L --data data/$data \
            --val-data data/line-panel-val --no-synthetic --no-plots --out $OUT/eval-L-$set
    done
done
[ -n "$1" ] && exit 0
$S compare --paired $OUT/eval-C-1139 $OUT/eval-L-1139 --out $OUT/paired-1139
for set in G E R; do $S compare --paired $R/eval-C-$set $OUT/eval-L-$set --out $OUT/paired-$set; done
