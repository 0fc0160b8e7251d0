#!/bin/bash
# Plan 69's tail with no idle core (stop 90): run.sh's fit and look run on one thread, so the rule's renders start
# beside them instead of after. Same commands as all.sh's; only their timing differs. Resumable: after a stop, run
# this alone (it restarts run.sh when it is not running and L63 has no threshold yet, and takes the committed L63/
# when there is one).
#   half 0 of the rule's renders once the threshold set is rendered (run.sh's val.done), beside the fit and the look;
#   half 1 once L63 has its threshold (run.sh done); then rule.sh (renders already done: the evaluations, decide.py).
set -euo pipefail
cd "$(dirname "$0")/../../.."  # the repository root
S=docs/results/2026-12-02-lobe-fit
R=runs/c88
running() { pgrep -f "lobe-fit/run.sh" > /dev/null; }
if [ ! -f $R/L63.done ] && [ -f $S/L63/L63.json ]; then  # L63 committed by an earlier stop (stop 91's amendment)
  .venv/bin/python -c "import sys; from model.draem.checkpoint import copy_checkpoint; copy_checkpoint(*sys.argv[1:])" \
    $S/L63/L63 $R/L63
  touch $R/L63.done
fi
if ! running && [ ! -f $R/L63.done ]; then
  $S/render.sh train  # all done already, unless data/ was lost
  $S/render.sh cal
  $S/run.sh > $R/run.log 2>&1 &
  sleep 5
fi
while [ ! -f $R/val.done ] && running; do sleep 30; done
$S/rule.sh render 0 > $R/rule-render-0.log 2>&1 &
while running; do sleep 30; done
[ -f $R/L63.done ] || { echo "run.sh ended without L63's threshold: see $R/L63.log, $R/L.log, $R/Lv.log"; exit 1; }
$S/rule.sh render 1 > $R/rule-render-1.log 2>&1
wait
$S/rule.sh
