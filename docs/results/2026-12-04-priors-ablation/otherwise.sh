#!/usr/bin/env bash
# The addendum's sets (plan.md) and reports, resumable: seed 1191's parts under a GGX lobe and a duller plastic, one
# render process each, then R, RAD and the shipped file E63 scored on both at their stored thresholds.
set -euo pipefail
cd "$(dirname "$0")"
ROOT=../../..
S=$ROOT/.venv/bin/station
export OMP_NUM_THREADS=1
V=(--config $ROOT/sim/presets/line-polar.toml --config $ROOT/sim/presets/variation.toml
   --config $ROOT/sim/presets/panel.toml --count 400 --seed 1191 --defects 0.6 --heldout)
$S render --out $ROOT/data/om-ggx-1191 "${V[@]}" \
    --materials '{"plastic": {"type": "pplastic", "finish": "smooth", "distribution": "ggx"}}' & a=$!
$S render --out $ROOT/data/om-rough-1191 "${V[@]}" --config ../2026-11-28-other-means/rough.toml & b=$!
wait $a; wait $b
for set in ggx rough; do
    for m in R:$ROOT/runs/abl/R-look RAD:$ROOT/runs/make-model-96/band-look E63:$ROOT/model/weights/default; do
        name=${m%%:*}
        [ -e "otherwise/eval-$name-$set/scores.csv" ] || $S eval --model "${m#*:}" --data "$ROOT/data/om-$set-1191" \
            --val-data $ROOT/data/line-pv-val --no-synthetic --out "otherwise/eval-$name-$set" &
    done
    wait
done
