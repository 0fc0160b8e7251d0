#!/bin/sh
# Rule 28's shipping (run from the repository root after render-28-ship.sh's training and validation sets): the
# shipped model's variation model fitted again on the panel line, evaluated on the held-out set seed 1130, copied to
# model/weights/default with its evaluation.
set -e
S=.venv/bin/station
mkdir -p runs/ship
[ -e runs/ship/panel.json ] || $S variation --model model/weights/default --refit --data data/line-panel-train \
    --val-data data/line-panel-val --decision variation --out runs/ship/panel
$S eval --model runs/ship/panel --data data/line-panel-heldout --val-data data/line-panel-val --out runs/ship/eval-panel
.venv/bin/python -c "import sys; from model.draem.checkpoint import copy_checkpoint; copy_checkpoint(*sys.argv[1:])" \
    runs/ship/panel model/weights/default
rm -rf model/weights/default-eval && mkdir model/weights/default-eval
cp runs/ship/eval-panel/eval.json runs/ship/eval-panel/eval.md runs/ship/eval-panel/*.png model/weights/default-eval/
# Once more after `station variation` began to record the fitted parts' frame statistics (the drift check's range;
# 2026-11-27 16:10): the same fit from the copied model into runs/ship2/panel, its held-out report identical, then
# copied and its report copied the same way.
