#!/bin/bash
# What heldout/nets.sh reads, from nothing (from anywhere; resumable: a finished sample or step is kept):
#   data/line-pf-train, data/line-pf-val   rule 62's sets (../render.sh train, ../render.sh val)
#   data/line-pv-val                       seed 303's 600 validation parts, the finish as built (make model's VAL)
#   data/line-panel-heldout-1165           the report set: seed 1165, 400 parts, the line as built
#   runs/r52/F/default                     the file before step 5 of model/weights/README.md (git show 0f17840^)
#   runs/r62/Fv                            rule 62's fit (../run.sh's command)
set -euo pipefail
cd "$(dirname "$0")/../../../.."  # the repository root
S=docs/results/2026-11-29-finish-vary
export OMP_NUM_THREADS=1
mkdir -p runs/r62 runs/r52/F
V="--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml"
two() {  # name, then station render's arguments: both shards, one per core
  name=$1; shift
  for k in 0 1; do
    .venv/bin/station render "$@" --out data/$name --shard $k/2 > runs/r62/render-$name-$k.log 2>&1 &
  done
  wait
}
$S/render.sh train
$S/render.sh val
two line-pv-val $V --config sim/presets/panel-vary.toml --count 600 --seed 303 --defects 0.4 --validation
two line-panel-heldout-1165 $V --count 400 --seed 1165 --defects 0.6 --heldout --visibility
for s in pt json; do
  [ -f runs/r52/F/default.$s ] || git show 0f17840^:model/weights/default.$s > runs/r52/F/default.$s
done
[ -f runs/r62/Fv.json ] || .venv/bin/station variation --model runs/r52/F/default --refit --data data/line-pf-train \
  --val-data data/line-pf-val --decision variation --out runs/r62/Fv > runs/r62/Fv.log 2>&1
