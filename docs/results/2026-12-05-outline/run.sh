#!/usr/bin/env bash
# plan.md's held-out reading: the shipped file before (B, a copy of model/weights/default as it was) and with the
# outline check (S: station shape on the variation model's own fit and calibration sets, then station threshold on
# VAL as make model does), each on seed 1202 (flash, never used) and on the good parts of the standard held-out line
# (seed 1197), read once. Resumable (a finished report is kept). Run from anywhere after the sets are rendered.
set -euo pipefail
HERE=$(cd "$(dirname "$0")" && pwd)
cd "$HERE/../../.."
R=runs/outline
mkdir -p "$R" "$HERE/eval"
export OMP_NUM_THREADS=1
[ -f "$R/B.json" ] || .venv/bin/python -c "import sys; from model.draem.checkpoint import copy_checkpoint; \
copy_checkpoint(*sys.argv[1:])" model/weights/default "$R/B"
if [ ! -f "$R/S.json" ]; then
    .venv/bin/station shape --model "$R/B" --data data/line-ef-train --val-data data/line-ef-val --out "$R/S-shaped" \
        > "$R/shape.log" 2>&1
    .venv/bin/python -c "import sys; from model.draem.checkpoint import copy_checkpoint; copy_checkpoint(*sys.argv[1:])" \
        "$R/S-shaped" "$R/S"
    .venv/bin/station threshold --model "$R/S" --data data/line-pv-val > "$R/threshold.log" 2>&1
fi
judge() {  # judge MODEL SET TAG: MODEL's report on SET into eval/TAG
    [ -f "$HERE/eval/$3/scores.csv" ] && return
    .venv/bin/station eval --model "$R/$1" --data "data/$2" --val-data data/line-pv-val --no-synthetic --no-plots \
        --out "$HERE/eval/$3" > "$R/eval-$3.log" 2>&1
}
judge B flash-1202 B-1202 & judge S flash-1202 S-1202; wait
judge B line-heldout-1197 B-1197 & judge S line-heldout-1197 S-1197; wait
(cd "$HERE" && PYTHONPATH=../../.. ../../../.venv/bin/python read.py > read.txt)
# the cost: both files in one run of the station's pipeline, on 300 frames of the report set, the machine otherwise idle
[ -f "$R/bench/pipeline.json" ] || env -u OMP_NUM_THREADS .venv/bin/station bench pipeline \
    --data data/line-panel-heldout-1194 --models "$R/B,$R/S" --methods bilinear --precisions fp32 \
    --parts 300 --out "$R/bench" > "$R/bench.log" 2>&1
cp "$R/bench/pipeline.md" "$R/bench/pipeline.json" "$HERE/"
