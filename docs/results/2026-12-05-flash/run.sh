#!/usr/bin/env bash
# plan.md: the shipped station on flash nobody rendered (seed 1200). Resumable (renders per sample; a finished report
# is kept). Run from anywhere; about 25 min of renders on 2 cores, then the reports.
set -euo pipefail
HERE=$(cd "$(dirname "$0")" && pwd)
cd "$HERE/../../.."
R=runs/flash
mkdir -p "$R" "$HERE/eval"
export OMP_NUM_THREADS=1
P=(--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml
   --config sim/presets/flash.toml --count 400 --seed 1200 --defects 0.6 --heldout --visibility)
for k in 0 1; do
    .venv/bin/station render --out data/flash-1200 "${P[@]}" --shard $k/2 > "$R/render-line-$k.log" 2>&1 &
done
wait
for k in 0 1; do
    .venv/bin/station render --out data/sw-flash-1200 "${P[@]}" --config sim/presets/side-view.toml --shard $k/2 \
        > "$R/render-side-$k.log" 2>&1 &
done
[ -f "$HERE/eval/line/scores.csv" ] || .venv/bin/station eval --model model/weights/default --data data/flash-1200 \
    --val-data data/line-pv-val --no-synthetic --out "$HERE/eval/line" > "$R/eval-line.log" 2>&1
wait
[ -f "$HERE/eval/side/scores.csv" ] || .venv/bin/station eval --model runs/side-intensity/side \
    --data data/sw-flash-1200 --val-data data/sw-pv-val --presence-rule row_contrast --no-synthetic --no-plots \
    --out "$HERE/eval/side" > "$R/eval-side.log" 2>&1
.venv/bin/station compare "$HERE/eval/line" "$HERE/eval/side" \
    --split docs/results/2026-12-05-side-intensity/split-SI.json --out "$R/pair" > "$R/compare.log" 2>&1
for x in md json; do sed "s|$PWD/||g" "$R/pair/two-cameras.$x" > "$HERE/pair.$x"; done
