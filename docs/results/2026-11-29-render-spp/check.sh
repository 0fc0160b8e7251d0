#!/bin/bash
# Check 62 (plan.md), from anywhere; resumable. Renders seed 1166 at 16, 64 and 8 spp on one core, once the
# held-out nets (../2026-11-29-finish-vary/heldout/) leave one free, then scores the shipped file on each.
set -euo pipefail
cd "$(dirname "$0")/../../.."  # the repository root
R=runs/c62
mkdir -p $R
export OMP_NUM_THREADS=1
V="--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml"
busy() { [ ! -f runs/r62/Fv.json ] || [ "$(pgrep -fc 'station (residual|eval|threshold)' || true)" -ge 2 ]; }
while busy || { sleep 60; busy; }; do  # a free core twice, a minute apart (not a worker between two steps)
  sleep 30
done
for spp in 16 64 8; do  # each scored as soon as it is rendered (16 first: check 62b reads it)
  [ -f $R/spp$spp.done ] || { .venv/bin/station render --out data/spp$spp-1166 $V --count 160 --seed 1166 \
    --defects 0.5 --heldout --spp $spp > $R/render-$spp.log 2>&1 && touch $R/spp$spp.done; }
  [ -f $R/eval-$spp/eval.md ] || .venv/bin/station eval --model model/weights/default --data data/spp$spp-1166 \
    --val-data data/line-pv-val --no-synthetic --no-plots --out $R/eval-$spp > $R/eval-$spp.log 2>&1
done
touch $R/check.done
