#!/usr/bin/env bash
# plan.md: seed 1196's codes through a camera's gamma (0.8, 1.25), the shipped file on each, the drift monitor on each.
# Run from anywhere; resumable (a finished sample or report is kept).
set -euo pipefail
HERE=$(cd "$(dirname "$0")" && pwd)
cd "$HERE/../../.."
R=runs/gamma
mkdir -p "$R" "$HERE/eval"
export OMP_NUM_THREADS=1 PYTHONPATH=.
for g in 08 125; do
    .venv/bin/python "$HERE/gamma.py" data/so-built-1196 "data/ga-g$g-1196" "$(echo "scale=2; $g / 10^(${#g} - 1)" | bc)"
done
.venv/bin/python "$HERE/drift_check.py" > "$HERE/drift-check.txt"
for g in 08 125; do
    out="$HERE/eval/S-g$g"
    [ -f "$out/eval.md" ] || .venv/bin/station eval --model model/weights/default --data "data/ga-g$g-1196" \
        --val-data data/line-pv-val --no-synthetic --no-plots --out "$out" > "$R/eval-g$g.log" 2>&1 &
done
wait
