#!/usr/bin/env bash
# plan.md: make side-model with the edge range, and the two-camera station on seed 1192 as built and chamfered 0.3 mm.
# Resumable (renders resume per sample; make side-model resumes; each report is kept).
set -euo pipefail
cd "$(dirname "$0")/../../.."  # the repository root
R=runs/c98
D=docs/results/2026-12-04-side-edges
mkdir -p $R
export OMP_NUM_THREADS=1
P=(--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml)
S=(--config sim/presets/side-view.toml)
H=(--count 400 --seed 1192 --defects 0.6 --heldout)
# the held-out twins on one process, beside make side-model (its renders run two, its fit one)
(.venv/bin/station render --out data/sw-heldout-1192 "${P[@]}" "${S[@]}" "${H[@]}"
 .venv/bin/station render --out data/sw-heldout-1192-e3 "${P[@]}" "${S[@]}" "${H[@]}" --edge-mm 0.3
 .venv/bin/station render --out data/line-heldout-1192-e3 "${P[@]}" "${H[@]}" --edge-mm 0.3) \
    > $R/render-heldout.log 2>&1 &
scripts/make-side-model.sh > $R/make-side-model.log 2>&1
wait
E=(--no-synthetic --no-plots)
line() {  # line SET NAME: the shipped line file on SET, thresholds from data/line-pv-val
    [ -f "$R/$2/scores.csv" ] || .venv/bin/station eval --model model/weights/default --data "$1" \
        --val-data data/line-pv-val "${E[@]}" --out "$R/$2" > "$R/$2.log" 2>&1
}
side() {  # side SET NAME: the side file on SET, thresholds from data/sw-pv-val
    [ -f "$R/$2/scores.csv" ] || .venv/bin/station eval --model runs/make-side-model/side --data "$1" \
        --val-data data/sw-pv-val --presence-rule row_contrast "${E[@]}" --out "$R/$2" > "$R/$2.log" 2>&1
}
mkdir -p $R/eval-line-1192
cp $D/../2026-12-04-priors-ablation/shipped/eval-E63-1192/scores.csv \
   $D/../2026-12-04-priors-ablation/shipped/eval-E63-1192/eval.json $R/eval-line-1192/  # as read there
side data/sw-heldout-1192 eval-side-1192 &
line data/line-heldout-1192-e3 eval-line-1192-e3
wait
side data/sw-heldout-1192-e3 eval-side-1192-e3
for s in 1192 1192-e3; do
    .venv/bin/station compare $R/eval-line-$s $R/eval-side-$s --split runs/make-side-model/split.json \
        --out $R/two-cameras-$s
done
mkdir -p $D/eval
for s in 1192 1192-e3; do
    cp $R/two-cameras-$s/two-cameras.md $D/two-cameras-$s.md
    cp $R/eval-side-$s/eval.md $D/eval/eval-side-$s.md
done
cp $R/eval-line-1192-e3/eval.md $D/eval/eval-line-1192-e3.md
cp runs/make-side-model/split.json $D/split.json
sha256sum runs/make-side-model/side.pt > $D/side.sha256
for s in 1192 1192-e3; do cp $R/two-cameras-$s/two-cameras.json $D/two-cameras-$s.json; done  # for plot.py
.venv/bin/python $D/plot.py
