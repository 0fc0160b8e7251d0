#!/bin/bash
# Rule 67 (plan.md), run by hand once the screen has passed; resumable. Renders R3 (seed 1186, round 0.3 mm edges,
# no chips) beside the first evaluations, then F63 (the shipped file) and E63 on S, E3 and R3, two at a time, and
# decide.py's verdict into decide67.txt.
set -euo pipefail
cd "$(dirname "$0")/../../.."  # the repository root
S=docs/results/2026-12-02-edge-range
R=runs/c86
export PYTHONPATH=. OMP_NUM_THREADS=1
V="--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml"
A="--count 400 --seed 1186 --defects 0.6 --heldout"
while pgrep -f "edge-range/run.sh" > /dev/null; do sleep 20; done  # lane B's renders of S and E3
ev() { [ -f $S/eval-$1/eval.md ] || .venv/bin/station eval --model $2 --data data/$3 --val-data data/line-pv-val \
  --no-synthetic --no-plots --out $S/eval-$1 > $R/eval-$1.log 2>&1; }
(ev F63-S86 model/weights/default line-panel-heldout-1186
 ev E63-S86 $R/E63 line-panel-heldout-1186
 ev F63-E3-86 model/weights/default edge03-heldout-1186) &
b=$!
if [ ! -f $R/round03.done ]; then
  .venv/bin/station render $V $A --edge-mm 0.3 --edge-shape round --config $S/no-chips.toml \
    --out data/round03-heldout-1186 > $R/round03.log 2>&1
  touch $R/round03.done
fi
ev E63-E3-86 $R/E63 edge03-heldout-1186
ev F63-R3-86 model/weights/default round03-heldout-1186
wait $b
ev E63-R3-86 $R/E63 round03-heldout-1186
.venv/bin/python $S/decide.py $S/eval-F63-S86 $S/eval-E63-S86 $S/eval-F63-E3-86 $S/eval-E63-E3-86 --ta 0.9785 \
  --tb $R/E63.json --also R3 $S/eval-F63-R3-86 $S/eval-E63-R3-86 --out $S/decide67.json > $S/decide67.txt
echo "rule done $(date +%T)"
