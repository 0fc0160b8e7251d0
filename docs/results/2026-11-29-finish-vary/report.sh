#!/bin/bash
# After rule 63 (from anywhere; resumable): the shipped file's report on seed 1165 (the line as built, rendered for
# it and used for nothing else; as render.sh of rule 60), the file before (K3) on the same parts, and the pipeline
# bench of both files in one run on seed 1164's frames.
set -euo pipefail
cd "$(dirname "$0")/../../.."  # the repository root
R=runs/r63
export PYTHONPATH=. OMP_NUM_THREADS=1
[ -f $R/eval-K3-1165/eval.md ] || .venv/bin/station eval --model runs/r59/K3 --data data/line-panel-heldout-1165 \
  --val-data data/line-pv-val --no-synthetic --no-plots --out $R/eval-K3-1165 > $R/eval-K3-1165.log 2>&1 &
[ -f $R/default-eval/eval.md ] || .venv/bin/station eval --model model/weights/default \
  --data data/line-panel-heldout-1165 --val-data data/line-pv-val --out $R/default-eval > $R/default-eval.log 2>&1
wait
[ -f $R/bench63/pipeline.json ] || .venv/bin/station bench pipeline --data data/line-panel-heldout-1164 \
  --models model/weights/default,runs/r59/K3 --methods bilinear --precisions fp32 --early-exit off --parts 150 \
  --out $R/bench63 > $R/bench63.log 2>&1
