#!/usr/bin/env bash
# plan.md: make side-model beside the shipped blend file, and the two-camera station on fresh seed 1245.
# Run from anywhere; resumable (renders resume per sample; make side-model resumes; a finished evaluation is kept).
set -euo pipefail
HERE=$(cd "$(dirname "$0")" && pwd)
cd "$HERE/../../.."
BIN=.venv/bin
R=runs/two-cameras-blend
mkdir -p "$R" "$HERE/eval"
export OMP_NUM_THREADS=1
echo 19 > /proc/self/autogroup 2>/dev/null || true  # beside the stop's other work, at the lowest priority
P=(--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml
   --count 400 --defects 0.6 --heldout --seed 1245)
SIDE=(--config sim/presets/side-view.toml)  # last: the side camera and its flat dome
scripts/make-side-model.sh > "$R/make-side-model.log" 2>&1
"$BIN/station" render --out data/line-heldout-1245 "${P[@]}" > "$R/render-line.log" 2>&1 &
"$BIN/station" render --out data/sw-heldout-1245 "${P[@]}" "${SIDE[@]}" > "$R/render-side.log" 2>&1 &
wait
cp runs/make-side-model/split.json "$HERE/split.json"
sha256sum runs/make-side-model/side.pt > "$HERE/side.sha256"
[ -f "$HERE/eval/line-1245/scores.csv" ] || "$BIN/station" eval --model model/weights/default \
    --data data/line-heldout-1245 --val-data data/line-pv-val --no-synthetic --no-plots \
    --out "$HERE/eval/line-1245" > "$R/eval-line.log" 2>&1 &
[ -f "$HERE/eval/side-1245/scores.csv" ] || "$BIN/station" eval --model runs/make-side-model/side \
    --data data/sw-heldout-1245 --val-data data/sw-pv-val --presence-rule row_contrast --no-synthetic --no-plots \
    --out "$HERE/eval/side-1245" > "$R/eval-side.log" 2>&1 &
wait
"$BIN/station" compare "$HERE/eval/line-1245" "$HERE/eval/side-1245" --split "$HERE/split.json" \
    --out "$R/two-cameras-1245" > "$R/compare.log" 2>&1
for x in md json; do cp "$R/two-cameras-1245/two-cameras.$x" "$HERE/two-cameras-1245.$x"; done
echo done > "$R/done"
