#!/bin/bash
# Rule 69 (plan.md), run once L63 has its threshold; resumable. Renders fresh seed 1190 three ways as plan 68's S,
# G and R (two processes, one half of every set each), then E63 (the shipped file) and L63 on each at their own
# thresholds, two at a time, and decide.py's verdict into decide69.txt. `rule.sh render K` renders half K only
# (overlap.sh starts it early, on the core the fit and the look leave idle).
set -euo pipefail
cd "$(dirname "$0")/../../.."  # the repository root
S=docs/results/2026-12-02-lobe-fit
R=runs/c88
export PYTHONPATH=. OMP_NUM_THREADS=1
V="--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml"
A="--count 400 --seed 1190 --defects 0.6 --heldout"
half() {  # shard k of 2 of every set
  k=$1
  [ -f $R/rule-render-$k.done ] && return
  .venv/bin/station render --out data/line-panel-heldout-1190 $V $A --shard $k/2
  .venv/bin/station render --out data/om-ggx-1190 $V $A --shard $k/2 \
    --materials '{"plastic": {"type": "pplastic", "finish": "smooth", "distribution": "ggx"}}'
  .venv/bin/station render --out data/om-rough-1190 $V $A --shard $k/2 \
    --config docs/results/2026-11-28-other-means/rough.toml
  touch $R/rule-render-$k.done
}
if [ "${1:-}" = render ]; then half "$2"; exit; fi  # one half alone: started early, on a core the look leaves idle
half 0 > $R/rule-render-0.log 2>&1 &
half 1 > $R/rule-render-1.log 2>&1 &
wait
ev() {  # file name, model, set
  [ -f $S/rule/eval-$1-$3-1190/eval.md ] || .venv/bin/station eval --model $2 --data data/$3-1190 \
    --no-synthetic --no-plots --out $S/rule/eval-$1-$3-1190 > $R/rule-eval-$1-$3.log 2>&1
  rm -f $S/rule/eval-$1-$3-1190/eval.json
}
for set in line-panel-heldout om-ggx om-rough; do
  ev E63 model/weights/default $set & p=$!
  ev L63 $R/L63 $set
  wait $p
done
r=$S/rule/eval
.venv/bin/python $S/decide.py --set S $r-E63-line-panel-heldout-1190 $r-L63-line-panel-heldout-1190 \
  --set G $r-E63-om-ggx-1190 $r-L63-om-ggx-1190 --set R $r-E63-om-rough-1190 $r-L63-om-rough-1190 \
  --ta model/weights/default.json --tb $R/L63.json --out $S/decide69.json > $S/decide69.txt
echo "rule done $(date +%T)"
