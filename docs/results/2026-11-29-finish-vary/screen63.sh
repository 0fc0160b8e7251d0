#!/bin/bash
# Rule 63's screen (plan.md's addendum), from anywhere; resumable. F63 is F with its threshold set again on the
# validation set as built (`station threshold` changes the threshold only: the look's calibration stays F's), so its
# scores on any set are F's: the screen reads rule 62's reports of F on seed 1163 at F63's threshold.
set -euo pipefail
cd "$(dirname "$0")/../../.."  # the repository root
R=runs/r63
mkdir -p $R
export PYTHONPATH=. OMP_NUM_THREADS=1
if [ ! -f $R/F63.json ]; then
  .venv/bin/python -c "from model.draem.checkpoint import copy_checkpoint; copy_checkpoint('runs/r62/F', '$R/F63t')"
  .venv/bin/station threshold --model $R/F63t --data data/line-pv-val > $R/F63.log 2>&1
  .venv/bin/python -c "from model.draem.checkpoint import copy_checkpoint; copy_checkpoint('$R/F63t', '$R/F63')"
fi
.venv/bin/python docs/results/2026-11-29-finish-vary/decide62.py runs/c61/eval-K3-{} runs/r62/eval-F-{}63 \
  --f-threshold $R/F63.json
