#!/usr/bin/env bash
# plan.md's addendum 2: both side files beside S on fresh seed 1195's kinds nobody rendered (the line camera's frames
# from the intensity-ship study, S's report copied; the side twins rendered here). Resumable.
set -euo pipefail
HERE=$(cd "$(dirname "$0")" && pwd)
cd "$HERE/../../.."
R=runs/side-intensity
export OMP_NUM_THREADS=1
for k in 0 1; do
    .venv/bin/station render --out data/sw-new-kinds-1195 --config sim/presets/line-polar.toml \
        --config sim/presets/variation.toml --config sim/presets/panel.toml --config sim/presets/new-kinds.toml \
        --count 400 --seed 1195 --defects 0.6 --heldout --visibility --config sim/presets/side-view.toml \
        --shard $k/2 > "$R/render-new-kinds-$k.log" 2>&1 &
done
wait
mkdir -p "$HERE/eval/line-nk"
cp "$HERE/../2026-12-04-intensity-ship/eval/S-new-kinds-1195/"{scores.csv,eval.json,eval.md} "$HERE/eval/line-nk/"
for f in SA:runs/make-side-model/side SI:$R/side; do
    [ -f "$HERE/eval/${f%%:*}-nk/scores.csv" ] || .venv/bin/station eval --model "${f#*:}" --data data/sw-new-kinds-1195 \
        --val-data data/sw-pv-val --presence-rule row_contrast --no-synthetic --no-plots --out "$HERE/eval/${f%%:*}-nk" \
        > "$R/eval-${f%%:*}-nk.log" 2>&1 &
done
wait
for f in SA SI; do
    .venv/bin/station compare "$HERE/eval/line-nk" "$HERE/eval/$f-nk" --split "$HERE/split-$f.json" \
        --out "$R/pair-$f-nk" > "$R/compare-$f-nk.log" 2>&1
    for x in md json; do sed "s|$PWD/||g" "$R/pair-$f-nk/two-cameras.$x" > "$HERE/pair-$f-nk.$x"; done
done
