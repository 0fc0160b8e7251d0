#!/bin/bash
# Plan 68's addendum (plan.md), from anywhere; resumable. After run.sh: fresh seed 1189, 400 parts of the kinds
# nobody trains on, the line camera only; E63 and F63 at their own thresholds. Then: python table.py runs/r68
set -euo pipefail
cd "$(dirname "$0")/../../.."  # the repository root
R=runs/r68
export PYTHONPATH=. OMP_NUM_THREADS=1
while [ ! -f $R/run.done ]; do sleep 30; done
V="--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml"
for k in 0 1; do
  # shellcheck disable=SC2086
  .venv/bin/station render --out data/new-kinds-1189 $V --config sim/presets/new-kinds.toml --count 400 --seed 1189 \
    --defects 0.6 --heldout --shard $k/2 > $R/render-new-kinds-$k.log 2>&1 &
done
wait
ev() {  # file name, model
  [ -f $R/eval-$1-new-kinds-1189/eval.md ] || .venv/bin/station eval --model $2 --data data/new-kinds-1189 \
    --no-synthetic --no-plots --out $R/eval-$1-new-kinds-1189 > $R/eval-$1-new-kinds-1189.log 2>&1
}
ev E63 model/weights/default & ev F63 $R/F63/default
wait
touch $R/newkinds.done
