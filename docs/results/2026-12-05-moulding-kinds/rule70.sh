#!/usr/bin/env bash
# rule-70-plan.md's held-out check: the shipped file with the shape check (C: station shape on the variation model's
# own fit and calibration sets) on each set once, against the shipped file's reports of the same parts. Resumable (a
# finished report is kept). Run from anywhere after run.sh.
set -euo pipefail
HERE=$(cd "$(dirname "$0")" && pwd)
cd "$HERE/../../.."
R=runs/shape
mkdir -p "$R" "$HERE/rule70"
export OMP_NUM_THREADS=1
[ -f "$R/C.json" ] || .venv/bin/station shape --model model/weights/default --data data/line-ef-train \
    --val-data data/line-ef-val --out "$R/C" > "$R/shape.log" 2>&1
cp "$R/C.json" "$HERE/rule70/C.json"
judge() {  # judge SET TAG: C's report on SET into rule70/TAG
    [ -f "$HERE/rule70/$2/scores.csv" ] && return
    .venv/bin/station eval --model "$R/C" --data "data/$1" --val-data data/line-pv-val --no-synthetic --no-plots \
        --out "$HERE/rule70/$2" > "$R/eval-$2.log" 2>&1
}
judge moulding-1198 C-1198 & judge line-panel-heldout-1194 C-1194; wait
judge ir-ggx-1193 C-ggx & judge ir-rough-1193 C-rough; wait
judge so-chamfer03-1196 C-chamfer03 & judge so-round03-1196 C-round03; wait
(cd "$HERE" && PYTHONPATH=../../.. ../../../.venv/bin/python read70.py > rule70/read.txt)
# bar 4: both files in one run of the station's pipeline, on 300 frames of the report set, the machine otherwise idle
[ -f "$R/bench/pipeline.json" ] || env -u OMP_NUM_THREADS .venv/bin/station bench pipeline \
    --data data/line-panel-heldout-1194 --models "model/weights/default,$R/C" --methods bilinear --precisions fp32 \
    --parts 300 --out "$R/bench" > "$R/bench.log" 2>&1
cp "$R/bench/pipeline.md" "$R/bench/pipeline.json" "$HERE/rule70/"
