#!/bin/bash
# Rule 62 (plan.md), from anywhere; resumable (finished steps are skipped). Two lanes, one per core, after the
# training render (render.sh train):
#   A: the validation set (both cores), F's fit and look network, then F's screen on check 61's used sets
#   B: seed 1164 rendered three ways for the rule (S as built, G GGX, R duller), as check 61 rendered seed 1163;
#      nothing reads it until the screen has passed (rule.sh)
set -euo pipefail
cd "$(dirname "$0")/../../.."  # the repository root
S=docs/results/2026-11-29-finish-vary
R=runs/r62
export PYTHONPATH=. OMP_NUM_THREADS=1
while pgrep -f "render.sh train" > /dev/null; do sleep 20; done
$S/render.sh val
V="--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml"
A="--count 400 --seed 1164 --defects 0.6 --heldout"
one() {  # name, then station render's arguments (a finished render is skipped)
  name=$1; shift
  [ -f $R/$name.done ] && return
  .venv/bin/station render "$@" --out data/$name > $R/$name.log 2>&1
  touch $R/$name.done
}
(one line-panel-heldout-1164 $V $A --visibility
 one om-ggx-1164 $V $A --materials '{"plastic": {"type": "pplastic", "finish": "smooth", "distribution": "ggx"}}'
 one om-rough-1164 $V $A --config docs/results/2026-11-28-other-means/rough.toml) &
ev() { [ -f $R/eval-$1/eval.md ] || .venv/bin/station eval --model $2 --data data/$3 --val-data data/line-pf-val \
  --no-synthetic --no-plots --out $R/eval-$1 > $R/eval-$1.log 2>&1; }
[ -f $R/Fv.json ] || .venv/bin/station variation --model runs/r52/F/default --refit --data data/line-pf-train \
  --val-data data/line-pf-val --decision variation --out $R/Fv > $R/Fv.log 2>&1
[ -f $R/F.json ] || .venv/bin/station residual --model $R/Fv --data data/line-pf-train --val-data data/line-pf-val \
  --members 1 --steps 3000 --second-look --out $R/F > $R/F.log 2>&1
ev F-S63 $R/F line-panel-heldout-1163
ev F-G63 $R/F om-ggx-1163
ev F-R63 $R/F om-rough-1163
touch $R/screen.done
wait
