#!/usr/bin/env bash
# plan.md's "what follows", when all four bars hold: `LOOK_DRAWS=3 make model` under the report protocol (held out seed
# 1194, kinds nobody rendered seed 1195, every held-out type), resumed from the shipped file's own variation model
# (stage 6 kept: runs/look-lens/s-variation, ../2026-12-10-look-lens/make-a.sh) and with the three draws the recipe
# trains on it already made by the same command (R, R1, R2 of ../2026-12-10-look-lens: `station residual ... --seed
# 0|1|2`, blended and thresholded on data/line-pv-val as make model's finish). make model then renders the report sets,
# trains the held-out types' looks, picks the draw (station pick on data/line-pv-val-lens), evaluates and ships.
# Resumable; at nice 19. S is kept first in the run folder (git checkout model/weights puts it back).
set -euo pipefail
HERE=$(cd "$(dirname "$0")" && pwd)
cd "$HERE/../../.."
BIN=.venv/bin
RUNS=runs/make-model-draw L=runs/look-lens
mkdir -p "$RUNS"
echo 19 > /proc/self/autogroup 2>/dev/null || true
export OMP_NUM_THREADS=1
copy() { [ -f "$2.json" ] || "$BIN/python" -c \
    "import sys; from model.draem.checkpoint import copy_checkpoint; copy_checkpoint(*sys.argv[1:])" "$1" "$2"; }
copy model/weights/default "$RUNS/s"
copy "$L/s-variation" "$RUNS/band-variation"
for n in 0 1 2; do copy "$L/R${n/#0/}" "$RUNS/band-look-draw-$n"; done
HELDOUT=data/line-panel-heldout-1194 HELDOUT_SEED=1194 NEW_KINDS=data/new-kinds-heldout-1195 NEW_KINDS_SEED=1195 \
    LOOK_DRAWS=3 RUNS=$RUNS SHIP=1 scripts/make-model.sh
"$BIN/station" eval --model "$RUNS/s" --data data/line-panel-heldout-1194 --val-data data/line-pv-val \
    --no-synthetic --out "$RUNS/eval-s-1194"
"$BIN/station" compare "$RUNS/eval-s-1194" model/weights/default-eval --paired --out "$RUNS/paired-1194"
echo "ship done $(date +%T)"
