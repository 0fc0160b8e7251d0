#!/usr/bin/env bash
# plan.md's addenda: seed 1196 with every edge broken (SHAPE chamfer: addendum 1, 0.3 mm; round: addendum 2, 0.3 mm,
# no chips), the side camera's twins, the files and split of run.sh. Resumable.   addendum.sh [chamfer|round]
set -euo pipefail
HERE=$(cd "$(dirname "$0")" && pwd)
cd "$HERE/../../.."
R=runs/two-cameras-intensity
mkdir -p "$R"
export OMP_NUM_THREADS=1
case "${1:-chamfer}" in
    chamfer) NAME=chamfer03 TAG=e3 EDGE=(--edge-mm 0.3) ;;
    round) NAME=round03 TAG=r3
           EDGE=(--edge-mm 0.3 --edge-shape round --config docs/results/2026-12-02-edge-range/no-chips.toml) ;;
    *) echo "addendum.sh: SHAPE is chamfer or round, not $1" >&2; exit 2 ;;
esac
for k in 0 1; do
    .venv/bin/station render --out "data/sw-$NAME-1196" --config sim/presets/line-polar.toml \
        --config sim/presets/variation.toml --config sim/presets/panel.toml --count 400 --seed 1196 --defects 0.6 \
        --heldout "${EDGE[@]}" --config sim/presets/side-view.toml --shard $k/2 > "$R/render-$NAME-$k.log" 2>&1 &
done
wait
mkdir -p "$HERE/eval/line-1196-$TAG"
cp "$HERE/../2026-12-04-ship-otherwise/eval/S-$NAME/"{scores.csv,eval.json,eval.md} "$HERE/eval/line-1196-$TAG/"
[ -f "$HERE/eval/side-1196-$TAG/scores.csv" ] || .venv/bin/station eval --model runs/make-side-model/side \
    --data "data/sw-$NAME-1196" --val-data data/sw-pv-val --presence-rule row_contrast --no-synthetic --no-plots \
    --out "$HERE/eval/side-1196-$TAG" > "$R/eval-side-1196-$TAG.log" 2>&1
.venv/bin/station compare "$HERE/eval/line-1196-$TAG" "$HERE/eval/side-1196-$TAG" --split "$HERE/split.json" \
    --out "$R/two-cameras-1196-$TAG" > "$R/compare-1196-$TAG.log" 2>&1
for x in md json; do
    sed 's#/work/main/##g' "$R/two-cameras-1196-$TAG/two-cameras.$x" > "$HERE/two-cameras-1196-$TAG.$x"
done
