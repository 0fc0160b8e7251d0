#!/bin/bash
# Plan 69's first half in one session (stop 91's amendment, plan.md), from anywhere; resumable. Waits for a
# render.sh train already running, renders the rest of L's sets, then run.sh with the threshold set rendered on one
# process beside the one-thread fit and look, and copies L63 into the repository (L63/) to be committed: the rule
# (rule.sh, seed 1190) runs against that copy in a later session even if data/ and runs/ are lost.
set -euo pipefail
cd "$(dirname "$0")/../../.."  # the repository root
S=docs/results/2026-12-02-lobe-fit
while pgrep -f "lobe-fit/render.sh train" > /dev/null; do sleep 20; done
"$S"/render.sh train
"$S"/render.sh cal
LANES=1 "$S"/run.sh
.venv/bin/python -c "import sys; from model.draem.checkpoint import copy_checkpoint; copy_checkpoint(*sys.argv[1:])" \
  runs/c88/L63 $S/L63/L63
echo "L63 copied $(date +%T)"
