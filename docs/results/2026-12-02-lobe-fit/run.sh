#!/bin/bash
# Plan 69 (plan.md), from anywhere; resumable (finished steps are skipped). After render.sh train and cal:
#   lane A: render.sh val (the line as built, for the threshold)
#   lane B: L's fit and its look network; then, once val is rendered, L63's threshold
# The rule's renders and evaluations (fresh seed 1190) are rule.sh (all.sh runs render.sh, run.sh, rule.sh).
set -euo pipefail
cd "$(dirname "$0")/../../.."  # the repository root
S=docs/results/2026-12-02-lobe-fit
R=runs/c88
export PYTHONPATH=. OMP_NUM_THREADS=1
while pgrep -f "lobe-fit/render.sh (train|cal)" > /dev/null; do sleep 20; done
if [ ! -d runs/r52/F ]; then  # the source of rules 62 and 67's fits: the file shipped before 0f17840
  mkdir -p runs/r52/F
  for x in json pt; do git show 0f17840^:model/weights/default.$x > runs/r52/F/default.$x; done
fi
[ -f $R/val.done ] || ($S/render.sh val && touch $R/val.done) &
a=$!
echo "fit $(date +%T)"
[ -f $R/Lv.json ] || .venv/bin/station variation --model runs/r52/F/default --refit --data data/line-lf-train \
  --val-data data/line-lf-val --decision variation --out $R/Lv > $R/Lv.log 2>&1
echo "look $(date +%T)"
[ -f $R/L.json ] || .venv/bin/station residual --model $R/Lv --data data/line-lf-train --val-data data/line-lf-val \
  --members 1 --steps 3000 --second-look --out $R/L > $R/L.log 2>&1
wait $a
if [ ! -f $R/L63.done ]; then  # rule 63: L's scores, thresholded on the line as built
  .venv/bin/python -c "import sys; from model.draem.checkpoint import copy_checkpoint; copy_checkpoint(*sys.argv[1:])" \
    $R/L $R/L63
  .venv/bin/station threshold --model $R/L63 --data data/line-pv-val > $R/L63.log 2>&1
  touch $R/L63.done
fi
# Amended at stop 89 (plan.md's amendment, before any fit or score of L): the screen is dropped, seed 1188's sets
# being lost with the machine; rule.sh follows (all.sh runs the whole chain).
echo "L63 done $(date +%T)"
