#!/bin/sh
# Rule 32, after render.sh (run from the repository root; each step is skipped when its output exists). P is rule
# 31's fit of the shipped line (runs/fl/P: made by docs/results/2026-11-27-front-light/models.sh, which also links
# data/fl-train-P and data/fl-val-P); R refits the shipped model's variation model on the fringe panel's sets.
set -e
S=.venv/bin/station
F=docs/results/2026-11-27-fringe-panel
L=docs/results/2026-11-27-front-light
[ -f runs/fl/P.json ] || { echo "runs/fl/P is missing: run $L/models.sh's P steps first" >&2; exit 1; }
[ -f runs/fr/R.json ] || $S variation --model model/weights/default --refit --data data/fr-train \
    --val-data data/fr-val --decision variation --out runs/fr/R
[ -f $F/eval-P/eval.json ] || $S eval --model runs/fl/P --data data/line-panel-heldout-1132 --val-data data/fl-val-P \
    --out $F/eval-P
[ -f $F/eval-R/eval.json ] || $S eval --model runs/fr/R --data data/fr-heldout --val-data data/fr-val --out $F/eval-R
$S compare --paired $F/eval-P $F/eval-R --out $F/paired
.venv/bin/python $L/groups.py $F/eval-P data/line-panel-heldout-1132 $F/eval-R data/fr-heldout $F/groups.json
cd docs/results/2026-11-27-bright-field && ../../../.venv/bin/python plot.py ../../../$F/eval-P \
    ../../../data/line-panel-heldout-1132 ../../../$F/eval-R ../../../data/fr-heldout \
    ../2026-11-27-fringe-panel.png "P: shipped line" "R: fringe panel" > ../../../$F/faces.md
mv faces-eval-R.json ../../../$F/faces.json
