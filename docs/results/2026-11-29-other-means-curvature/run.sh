#!/bin/bash
# Check 61 (plan.md), from the repository root; resumable. Waits for seed 1163's render, renders G and R of the same
# parts, then evaluates the shipped file (K3) and the file before (C) on S, G and R.
set -euo pipefail
S=docs/results/2026-11-29-other-means-curvature
R=runs/c61
mkdir -p $R
while pgrep -f "line-panel-heldout-1163 " > /dev/null; do sleep 20; done
V="--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml"
A="--count 400 --seed 1163 --defects 0.6 --heldout"
two() {  # name, then station render's arguments: both shards, one per core (a finished render is skipped)
  name=$1; shift
  [ -f $R/$name.done ] && return
  OMP_NUM_THREADS=1 .venv/bin/station render "$@" --out data/$name --shard 0/2 > $R/$name-0.log 2>&1 &
  OMP_NUM_THREADS=1 .venv/bin/station render "$@" --out data/$name --shard 1/2 > $R/$name-1.log 2>&1
  wait
  touch $R/$name.done
}
export PYTHONPATH=. OMP_NUM_THREADS=1
ev() { [ -f $R/eval-$1/eval.md ] || .venv/bin/station eval --model $2 --data data/$3 --val-data data/line-pv-val \
  --no-synthetic --no-plots --out $R/eval-$1 > $R/eval-$1.log 2>&1; }
(ev K3-S model/weights/default line-panel-heldout-1163; ev C-S runs/r59/Ccopy line-panel-heldout-1163) &
two om-ggx-1163 $V $A --materials '{"plastic": {"type": "pplastic", "finish": "smooth", "distribution": "ggx"}}'
wait
(ev K3-G model/weights/default om-ggx-1163; ev C-G runs/r59/Ccopy om-ggx-1163) &
two om-rough-1163 $V $A --config docs/results/2026-11-28-other-means/rough.toml
wait
(ev K3-R model/weights/default om-rough-1163) &
ev C-R runs/r59/Ccopy om-rough-1163
wait
