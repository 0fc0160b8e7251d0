#!/bin/bash
# Plan 68's sets (plan.md), from anywhere; resumable (a finished sample is skipped). Two processes, one per core,
# each rendering one half of every set in turn; then S re-exposed through the lens (B) and all five imperfections (I).
set -euo pipefail
cd "$(dirname "$0")/../../.."  # the repository root
R=runs/r68
O=docs/results
V="--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml"
A="--count 400 --seed 1188 --defects 0.6 --heldout"
export PYTHONPATH=. OMP_NUM_THREADS=1
mkdir -p $R
half() {  # shard k of 2 of every set
  k=$1
  .venv/bin/station render --out data/line-panel-heldout-1188 $V $A --shard $k/2
  .venv/bin/station render --out data/om-ggx-1188 $V $A --shard $k/2 \
    --materials '{"plastic": {"type": "pplastic", "finish": "smooth", "distribution": "ggx"}}'
  .venv/bin/station render --out data/om-rough-1188 $V $A --shard $k/2 --config $O/2026-11-28-other-means/rough.toml
  .venv/bin/station render --out data/pb-half-1188 $V $A --shard $k/2 --config $O/2026-11-29-panel-brightness/half.toml
}
half 0 > $R/render-0.log 2>&1 &
half 1 > $R/render-1.log 2>&1 &
wait
for kind in blur all; do
  [ -f $R/reexpose-$kind.done ] && continue  # the script writes its manifest first: a marker says it ended
  .venv/bin/python $O/2026-11-29-fireflies/reexpose.py data/line-panel-heldout-1188 data/so-${kind}ff-1188 $kind \
    > $R/reexpose-$kind.log 2>&1
  touch $R/reexpose-$kind.done
done
touch $R/render.done
