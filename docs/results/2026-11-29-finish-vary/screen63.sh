#!/bin/bash
# Rule 63's screen (plan.md's addendum), from anywhere; resumable: F with thresholds from data/line-pv-val on seed
# 1163's used S, G and R. Then: python decide62.py runs/c61/eval-K3-{} runs/r63/eval-F63-{}63
set -euo pipefail
cd "$(dirname "$0")/../../.."  # the repository root
R=runs/r63
mkdir -p $R
export PYTHONPATH=. OMP_NUM_THREADS=1
ev() { [ -f $R/eval-$1/eval.md ] || .venv/bin/station eval --model runs/r62/F --data data/$2 --val-data data/line-pv-val \
  --no-synthetic --no-plots --out $R/eval-$1 > $R/eval-$1.log 2>&1; }
ev F63-S63 line-panel-heldout-1163
ev F63-G63 om-ggx-1163
ev F63-R63 om-rough-1163
