#!/bin/sh
# Rule 33, after render.sh (run from the repository root; each step is skipped when its output exists). P is rule
# 31's fit of the shipped line (runs/fl/P: made by docs/results/2026-11-27-front-light/models.sh, which also links
# data/fl-train-P and data/fl-val-P); Q refits the shipped model's variation model on the light plate's sets.
set -e
S=.venv/bin/station
D=docs/results/2026-11-27-light-plate
L=docs/results/2026-11-27-front-light
[ -f runs/fl/P.json ] || { echo "runs/fl/P is missing: run $L/models.sh's P steps first" >&2; exit 1; }
[ -f runs/lp/Q.json ] || $S variation --model model/weights/default --refit --data data/lp-train \
    --val-data data/lp-val --decision variation --out runs/lp/Q
[ -f $D/eval-P/eval.json ] || $S eval --model runs/fl/P --data data/line-panel-heldout-1133 --val-data data/fl-val-P \
    --out $D/eval-P
[ -f $D/eval-Q/eval.json ] || $S eval --model runs/lp/Q --data data/lp-heldout --val-data data/lp-val --out $D/eval-Q
$S compare --paired $D/eval-P $D/eval-Q --out $D/paired
.venv/bin/python $L/groups.py $D/eval-P data/line-panel-heldout-1133 $D/eval-Q data/lp-heldout $D/groups.json
cd docs/results/2026-11-27-bright-field && ../../../.venv/bin/python plot.py ../../../$D/eval-P \
    ../../../data/line-panel-heldout-1133 ../../../$D/eval-Q ../../../data/lp-heldout \
    ../2026-11-27-light-plate.png "P: shipped line" "Q: light plate" > ../../../$D/faces.md
mv faces-eval-Q.json ../../../$D/faces.json
