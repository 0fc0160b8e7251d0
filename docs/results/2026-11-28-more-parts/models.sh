#!/bin/sh
# Rule 44 (run from the repository root; each step is skipped when its output exists): C and X evaluated on seed 1144
# unshifted and shifted, X on rules 35-36's sets G, E, R (C's reports there are rule 43's eval-X-*); then the paired
# comparisons and the pipeline bench. `models.sh C` or `models.sh X` runs one model's evaluations only.
# X: station variation --model model/weights/default --refit --data data/line-panel-train-1800
#      --val-data data/line-panel-val --decision variation --out runs/r44/X
# seed 1144: station render --config sim/presets/line-polar.toml --config sim/presets/variation.toml
#   --config sim/presets/panel.toml --count 400 --seed 1144 --defects 0.6 --heldout
#   --out data/line-panel-heldout-1144 (--shard 0/2 and 1/2)
set -e
S=.venv/bin/station
OUT=docs/results/2026-11-28-more-parts
R=docs/results/2026-11-28-native-units
SHIFTS="none,gamma 1.25,dolp x0.5,blur 1 px,rotate 5 deg,zoom x1.05"
model() { [ "$1" = C ] && echo model/weights/default || echo runs/r44/X; }
for m in ${1:-C X}; do
    [ -f $OUT/eval-$m-1144/eval.json ] || $S eval --model $(model $m) --data data/line-panel-heldout-1144 \
        --val-data data/line-panel-val --no-plots --out $OUT/eval-$m-1144
    [ -f $OUT/shift-$m/shift.json ] || $S bench shift --model $(model $m) --data data/line-panel-heldout-1144 \
        --val-data data/line-panel-val --shifts "$SHIFTS" --out $OUT/shift-$m
    [ $m = C ] && continue
    for x in G:om-ggx E:om-ior R:om-rough; do
        set=${x%%:*}; data=${x#*:}
        [ -f $OUT/eval-X-$set/eval.json ] || $S eval --model runs/r44/X --data data/$data \
            --val-data data/line-panel-val --no-synthetic --no-plots --out $OUT/eval-X-$set
    done
done
[ -n "$1" ] && exit 0
$S compare --paired $OUT/eval-C-1144 $OUT/eval-X-1144 --out $OUT/paired-1144
for set in G E R; do $S compare --paired $R/eval-X-$set $OUT/eval-X-$set --out $OUT/paired-$set; done
# (d): both files in one run, the cores otherwise idle
[ -f $OUT/bench-X/pipeline.json ] || $S bench pipeline --data data/line-panel-heldout-1144 \
    --models model/weights/default,runs/r44/X --methods bilinear --precisions fp32 --presence on --parts 150 \
    --out $OUT/bench-X
