#!/usr/bin/env bash
# plan.md's addendum 2: seed 1196 rounded 0.3 mm (no chips), the side twins, the files and split of run.sh. Resumable.
set -euo pipefail
HERE=$(cd "$(dirname "$0")" && pwd)
cd "$HERE/../../.."
R=runs/two-cameras-intensity
mkdir -p "$R"
export OMP_NUM_THREADS=1
for k in 0 1; do
    .venv/bin/station render --out data/sw-round03-1196 --config sim/presets/line-polar.toml \
        --config sim/presets/variation.toml --config sim/presets/panel.toml --count 400 --seed 1196 --defects 0.6 \
        --heldout --edge-mm 0.3 --edge-shape round --config docs/results/2026-12-02-edge-range/no-chips.toml \
        --config sim/presets/side-view.toml --shard $k/2 > "$R/render-round-$k.log" 2>&1 &
done
wait
mkdir -p "$HERE/eval/line-1196-r3"
cp "$HERE/../2026-12-04-ship-otherwise/eval/S-round03/"{scores.csv,eval.json,eval.md} "$HERE/eval/line-1196-r3/"
[ -f "$HERE/eval/side-1196-r3/scores.csv" ] || .venv/bin/station eval --model runs/make-side-model/side \
    --data data/sw-round03-1196 --val-data data/sw-pv-val --presence-rule row_contrast --no-synthetic --no-plots \
    --out "$HERE/eval/side-1196-r3" > "$R/eval-side-1196-r3.log" 2>&1
.venv/bin/station compare "$HERE/eval/line-1196-r3" "$HERE/eval/side-1196-r3" --split "$HERE/split.json" \
    --out "$R/two-cameras-1196-r3" > "$R/compare-1196-r3.log" 2>&1
for x in md json; do sed 's#/work/main/##g' "$R/two-cameras-1196-r3/two-cameras.$x" > "$HERE/two-cameras-1196-r3.$x"; done
