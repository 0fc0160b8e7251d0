#!/usr/bin/env bash
# plan.md: seed 1196 re-exposed through a lens out of focus (1.0, 1.5, 2.0 px), the shipped file on each, and the
# candidate statistic through the drift monitor. Run from anywhere; resumable (a finished sample or report is kept).
# STEP=reexpose|eval|check|all (default).
set -euo pipefail
HERE=$(cd "$(dirname "$0")" && pwd)
cd "$HERE/../../.."
BIN=.venv/bin
R=runs/focus
mkdir -p "$R" "$HERE/eval"
export OMP_NUM_THREADS=1 PYTHONPATH=.
STEP=${STEP:-all}
SIGMAS=(10 15 20)  # tenths of a frame pixel
if [ "$STEP" = reexpose ] || [ "$STEP" = all ]; then
    for s in "${SIGMAS[@]}"; do
        "$BIN/python" "$HERE/reexpose.py" data/so-built-1196 "data/fo-blur$s-1196" "$(echo "scale=1; $s / 10" | bc)" \
            > "$R/reexpose-$s.log" 2>&1
    done
fi
if [ "$STEP" = eval ] || [ "$STEP" = all ]; then
    for s in "${SIGMAS[@]}"; do
        out="$HERE/eval/S-blur$s"
        [ -f "$out/eval.md" ] || "$BIN/station" eval --model model/weights/default --data "data/fo-blur$s-1196" \
            --val-data data/line-pv-val --no-synthetic --no-plots --out "$out" > "$R/eval-blur$s.log" 2>&1
    done
fi
if [ "$STEP" = check ] || [ "$STEP" = all ]; then
    "$BIN/python" "$HERE/focus_check.py" > "$HERE/focus-check.txt"
fi
