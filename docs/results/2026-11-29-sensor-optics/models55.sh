#!/bin/bash
# Rule 55 (rule55.md), from the repository root; resumable. Needs runs/r54/Z and data/line-panel-heldout-1158.
set -euo pipefail
S=docs/results/2026-11-29-sensor-optics
export PYTHONPATH=. OMP_NUM_THREADS=1
mkdir -p runs/r55
[ -f runs/r55/Zp.json ] || { .venv/bin/python -c "import sys; from model.draem.checkpoint import copy_checkpoint; copy_checkpoint(*sys.argv[1:])" runs/r54/Z runs/r55/Zp
    .venv/bin/station threshold --model runs/r55/Zp --data data/line-pv-val; }
[ -f data/so-all-1158/samples/000399/raw.png ] || .venv/bin/python $S/resensor.py data/line-panel-heldout-1158 data/so-all-1158 all
ev() {  # ev NAME MODEL: both sets
    [ -f runs/r55/eval-$1-1158/eval.md ] || .venv/bin/station eval --model $2 --data data/line-panel-heldout-1158 \
        --val-data data/line-pv-val --out runs/r55/eval-$1-1158
    [ -f runs/r55/eval-$1-all/eval.md ] || .venv/bin/station eval --model $2 --data data/so-all-1158 \
        --val-data data/line-pv-val --no-synthetic --out runs/r55/eval-$1-all
}
ev Zp runs/r55/Zp & ev X model/weights/default & wait
.venv/bin/python $S/decide55.py runs/r55/eval-Zp-1158 runs/r55/eval-X-1158 runs/r55/eval-Zp-all runs/r55/eval-X-all \
    runs/r55/Zp | tee $S/decide55.md
