#!/bin/bash
# Rule 67 (plan.md), from anywhere; resumable (finished steps are skipped). After render.sh train and val:
#   lane A: E's fit, its look network, E63's threshold, then the screen on seed 1184's used sets
#   lane B: seed 1186 rendered as built (S) and with 0.3 mm edges (E3); nothing reads it before the screen passes
# The rule's evaluations are rule.sh, run by hand once the screen has passed.
set -euo pipefail
cd "$(dirname "$0")/../../.."  # the repository root
S=docs/results/2026-12-02-edge-range
R=runs/c86
export PYTHONPATH=. OMP_NUM_THREADS=1
while pgrep -f "render.sh" > /dev/null; do sleep 20; done
V="--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml"
A="--count 400 --seed 1186 --defects 0.6 --heldout"
one() {  # name, then station render's arguments (a finished render is skipped)
  name=$1; shift
  [ -f $R/$name.done ] && return
  .venv/bin/station render "$@" --out data/$name > $R/$name.log 2>&1
  touch $R/$name.done
}
(one line-panel-heldout-1186 $V $A --visibility
 one edge03-heldout-1186 $V $A --edge-mm 0.3) &
ev() { [ -f $R/eval-$1/eval.md ] || .venv/bin/station eval --model $2 --data data/$3 --val-data data/line-pv-val \
  --no-synthetic --no-plots --out $R/eval-$1 > $R/eval-$1.log 2>&1; }
echo "fit $(date +%T)"
[ -f $R/Ev.json ] || .venv/bin/station variation --model runs/r52/F/default --refit --data data/line-ef-train \
  --val-data data/line-ef-val --decision variation --out $R/Ev > $R/Ev.log 2>&1
echo "look $(date +%T)"
[ -f $R/E.json ] || .venv/bin/station residual --model $R/Ev --data data/line-ef-train --val-data data/line-ef-val \
  --members 1 --steps 3000 --second-look --out $R/E > $R/E.log 2>&1
if [ ! -f $R/E63.done ]; then  # rule 63: E's scores, thresholded on the line as built
  .venv/bin/python -c "import sys; from model.draem.checkpoint import copy_checkpoint; copy_checkpoint(*sys.argv[1:])" \
    $R/E $R/E63
  .venv/bin/station threshold --model $R/E63 --data data/line-pv-val > $R/E63.log 2>&1
  touch $R/E63.done
fi
echo "screen $(date +%T)"
ev E63-S84 $R/E63 line-panel-heldout-1184 & p=$!
ev E63-E3-84 $R/E63 edge03-heldout-1184
wait $p
ev E63-E1-84 $R/E63 edge01-heldout-1184
wait
echo "all done $(date +%T)"
