#!/bin/bash
# rule 52's renders (rule52.md), in order, each two shards at once (resumable: rerun this script)
cd "$(dirname "$0")/../../.."  # the repository root
P="--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml"
two() { OMP_NUM_THREADS=1 station render --shard 0/2 "$@" > runs/r52/q-$(basename $2)-0.log 2>&1 &
        OMP_NUM_THREADS=1 station render --shard 1/2 "$@" > runs/r52/q-$(basename $2)-1.log 2>&1; wait; }
two --out data/line-pv-train $P --config docs/results/2026-11-29-panel-brightness/panel-vary.toml --count 900 --seed 101 --defects 0.4 --defects-in-train
two --out data/line-pv-val $P --config docs/results/2026-11-29-panel-brightness/panel-vary.toml --count 600 --seed 303 --defects 0.4 --validation
two --out data/line-panel-heldout-1154 $P --count 400 --seed 1154 --defects 0.6 --heldout --visibility
two --out data/pb-half-1154 $P --config docs/results/2026-11-29-panel-brightness/half.toml --count 400 --seed 1154 --defects 0.6 --heldout
echo queue done
