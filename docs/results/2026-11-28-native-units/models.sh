#!/bin/sh
# Rule 43 (run from the repository root; each step is skipped when its output exists): C and X evaluated on seed 1142
# unshifted and shifted, X on rules 35-36's sets G, E, R; then the paired comparisons. `models.sh C` or `models.sh X`
# runs one model's evaluations only. X (runs/r43/MLBN) was fitted for the screen in
# docs/results/2026-11-28-contrast-mean/why/native-units/ (code at commit 1dbb773 or later):
#   station variation --model model/weights/default --refit --data data/line-panel-train --val-data data/line-panel-val
#     --decision variation --global-contrast mean --clusters 8 --blur-copies 1.5 --out runs/r43/MLBN
# seed 1142: station render --config sim/presets/line-polar.toml --config sim/presets/variation.toml
#   --config sim/presets/panel.toml --count 400 --seed 1142 --defects 0.6 --heldout
#   --out data/line-panel-heldout-1142 (--shard 0/2, then 1/2)
set -e
S=.venv/bin/station
OUT=docs/results/2026-11-28-native-units
R=docs/results/2026-11-28-polarization-range
SHIFTS="none,gamma 1.25,gamma 0.8,dolp x0.5,dolp x2,aolp +5 deg,blur 1 px,blur 0.5 px,rotate 5 deg,zoom x1.05"
model() { [ "$1" = C ] && echo model/weights/default || echo runs/r43/MLBN; }
for m in ${1:-C X}; do
    [ -f $OUT/eval-$m-1142/eval.json ] || $S eval --model $(model $m) --data data/line-panel-heldout-1142 \
        --val-data data/line-panel-val --no-plots --out $OUT/eval-$m-1142
    [ -f $OUT/shift-$m/shift.json ] || $S bench shift --model $(model $m) --data data/line-panel-heldout-1142 \
        --val-data data/line-panel-val --shifts "$SHIFTS" --out $OUT/shift-$m
    [ $m = C ] && continue
    for x in G:om-ggx E:om-ior R:om-rough; do
        set=${x%%:*}; data=${x#*:}
        [ -f $OUT/eval-X-$set/eval.json ] || $S eval --model runs/r43/MLBN --data data/$data \
            --val-data data/line-panel-val --no-synthetic --no-plots --out $OUT/eval-X-$set
    done
done
[ -n "$1" ] && exit 0
$S compare --paired $OUT/eval-C-1142 $OUT/eval-X-1142 --out $OUT/paired-1142
for set in G E R; do $S compare --paired $R/eval-C-$set $OUT/eval-X-$set --out $OUT/paired-$set; done
# (e): both files in one run, the cores otherwise idle
[ -f $OUT/bench-X/pipeline.json ] || $S bench pipeline --data data/line-panel-heldout-1142 \
    --models model/weights/default,runs/r43/MLBN --methods bilinear --precisions fp32 --presence on --parts 150 \
    --out $OUT/bench-X
