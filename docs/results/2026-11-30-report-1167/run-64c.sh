#!/bin/bash
# Check 64c (plan-64c.md), from anywhere; resumable. Seed 1167's 400 parts again without stray light, then the
# shipped file on them, paired with check 64's report.
set -euo pipefail
cd "$(dirname "$0")/../../.."  # the repository root
S=docs/results/2026-11-30-report-1167
R=runs/c64c
mkdir -p $R
export OMP_NUM_THREADS=1
V="--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml"
for k in ${SHARDS:-0 1}; do
  .venv/bin/station render $V --config $S/no-stray.toml --count 400 --seed 1167 --defects 0.6 --heldout --visibility \
    --out data/line-panel-heldout-1167-B --shard $k/2 > $R/render-$k.log 2>&1 &
done
wait
.venv/bin/python $S/score64c.py > $S/shielded-1167.md
