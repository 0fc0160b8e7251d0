#!/bin/sh
# Rule 39 (run from the repository root; each step is skipped when its output exists): the held-out set of seed 1138,
# D fitted from the shipped model (C), both evaluated on seed 1138 unshifted and shifted, D on rules 35-36's sets
# G, E, R; then the paired comparisons. `models.sh C` or `models.sh D` runs one model's evaluations only.
set -e
S=.venv/bin/station
D=docs/results/2026-11-28-blur-copies-range
R=docs/results/2026-11-28-polarization-range
V="--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml"
mkdir -p runs/r39
[ -f runs/r39/render-1138.done ] || { for i in 0 1; do
    $S render $V --count 400 --seed 1138 --defects 0.6 --heldout --out data/line-panel-heldout-1138 --shard $i/2 &
    done; wait; touch runs/r39/render-1138.done; }
[ -f runs/r39/D.json ] || $S variation --model model/weights/default --refit --data data/line-panel-train \
    --val-data data/line-panel-val --decision variation --blur-copies 1.5 --out runs/r39/D
SHIFTS="none,blur 1 px,dolp x0.5,dolp x2,aolp +5 deg,gamma 1.25,blur 0.5 px,rotate 5 deg,zoom x1.05"
model() { [ "$1" = C ] && echo model/weights/default || echo runs/r39/D; }
for m in ${1:-C D}; do
    [ -f $D/eval-$m-1138/eval.json ] || $S eval --model $(model $m) --data data/line-panel-heldout-1138 \
        --val-data data/line-panel-val --no-plots --out $D/eval-$m-1138
    [ -f $D/shift-$m/shift.json ] || $S bench shift --model $(model $m) --data data/line-panel-heldout-1138 \
        --val-data data/line-panel-val --shifts "$SHIFTS" --out $D/shift-$m
    [ $m = C ] && continue
    for x in G:om-ggx E:om-ior R:om-rough; do
        set=${x%%:*}; data=${x#*:}
        [ -f $D/eval-D-$set/eval.json ] || $S eval --model runs/r39/D --data data/$data \
            --val-data data/line-panel-val --no-synthetic --no-plots --out $D/eval-D-$set
    done
done
[ -n "$1" ] && exit 0
$S compare --paired $D/eval-C-1138 $D/eval-D-1138 --out $D/paired-1138
for set in G E R; do $S compare --paired $R/eval-C-$set $D/eval-D-$set --out $D/paired-$set; done
