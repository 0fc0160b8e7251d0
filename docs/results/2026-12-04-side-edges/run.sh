#!/usr/bin/env bash
# plan.md: make side-model with the edge range, and the two-camera station on seed 1192 as built and chamfered 0.3 mm.
# Resumable (renders resume per sample; make side-model resumes; each report is kept).
source "$(dirname "$0")/common.sh"
H=(--count 400 --seed 1192 --defects 0.6 --heldout)
# the held-out twins on one process, beside make side-model (its renders run two, its fit one)
(.venv/bin/station render --out data/sw-heldout-1192 "${P[@]}" "${S[@]}" "${H[@]}"
 .venv/bin/station render --out data/sw-heldout-1192-e3 "${P[@]}" "${S[@]}" "${H[@]}" --edge-mm 0.3
 .venv/bin/station render --out data/line-heldout-1192-e3 "${P[@]}" "${H[@]}" --edge-mm 0.3) \
    > $R/render-heldout.log 2>&1 &
scripts/make-side-model.sh > $R/make-side-model.log 2>&1
wait
ablation_line 1192
side data/sw-heldout-1192 1192 &
line data/line-heldout-1192-e3 1192-e3
wait
side data/sw-heldout-1192-e3 1192-e3
pair 1192
pair 1192-e3
cp runs/make-side-model/split.json $D/split.json
sha256sum runs/make-side-model/side.pt > $D/side.sha256
.venv/bin/python $D/plot.py
