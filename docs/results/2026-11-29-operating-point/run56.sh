#!/bin/bash
# Rule 56 (rule56.md), from the repository root; resumable. Needs data/line-panel-heldout-1159 rendered.
set -euo pipefail
S=docs/results/2026-11-29-operating-point
export PYTHONPATH=. OMP_NUM_THREADS=1
mkdir -p runs/r56
[ -f data/so-all-1159/samples/000399/raw.png ] || .venv/bin/python docs/results/2026-11-29-sensor-optics/resensor.py \
    data/line-panel-heldout-1159 data/so-all-1159 all
[ -f runs/r56/eval-X-1159/eval.md ] || .venv/bin/station eval --model model/weights/default \
    --data data/line-panel-heldout-1159 --val-data data/line-pv-val --out runs/r56/eval-X-1159 &
[ -f runs/r56/eval-X-all/eval.md ] || .venv/bin/station eval --model model/weights/default --data data/so-all-1159 \
    --val-data data/line-pv-val --no-synthetic --out runs/r56/eval-X-all &
wait
.venv/bin/python $S/decide56.py runs/r56/eval-X-1159 runs/r56/eval-X-all | tee $S/decide56.md
