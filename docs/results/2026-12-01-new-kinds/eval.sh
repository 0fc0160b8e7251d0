#!/usr/bin/env bash
# plan.md's measurement: the shipped file on the new kinds' set, thresholds from the line's validation set.
set -euo pipefail
D=docs/results/2026-12-01-new-kinds
R=runs/c76
mkdir -p $R
[ -f $R/eval-new-kinds/scores.csv ] || .venv/bin/station eval --model model/weights/default \
  --data data/new-kinds-1179 --val-data data/line-pv-val --no-synthetic --out $R/eval-new-kinds \
  > $R/eval-new-kinds.log 2>&1
mkdir -p $D/eval
cp $R/eval-new-kinds/eval.md $R/eval-new-kinds/eval.json $R/eval-new-kinds/scores.csv $D/eval/
cp $R/eval-new-kinds/*.png $D/eval/ 2>/dev/null || true
