#!/bin/bash
# Check 67's confirmation seed (plan.md), from anywhere; resumable. Waits until run.sh's fits have begun, so its
# renders take the core the fits leave idle; scores once S exists.
set -euo pipefail
cd "$(dirname "$0")/../../.."  # the repository root
R=runs/c67
mkdir -p $R
export OMP_NUM_THREADS=1
V="--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml"
SV="--config sim/presets/side-view.toml"
until [ -f $R/S2.log ]; do sleep 30; done
.venv/bin/station render --out data/line-panel-heldout-1169 $V --count 400 --seed 1169 --defects 0.6 --heldout \
  > $R/render-line-1169.log 2>&1
.venv/bin/station render --out data/sv-heldout-1169 $V $SV --count 400 --seed 1169 --defects 0.6 --heldout \
  > $R/render-side-1169.log 2>&1
[ -f $R/eval-line-1169/scores.csv ] || .venv/bin/station eval --model model/weights/default \
  --data data/line-panel-heldout-1169 --val-data data/line-pv-val --no-synthetic --no-plots --out $R/eval-line-1169 \
  > $R/eval-line-1169.log 2>&1
until [ -f $R/done ]; do sleep 30; done
[ -f $R/eval-S-1169/scores.csv ] || .venv/bin/station eval --model $R/S --data data/sv-heldout-1169 \
  --val-data data/sv-pv-val --no-synthetic --no-plots --out $R/eval-S-1169 > $R/eval-S-1169.log 2>&1
.venv/bin/python docs/results/2026-11-30-front-view/compare66.py $R/eval-line-1169 data/line-panel-heldout-1169 \
  $R/eval-S-1169 $R/val-default $R/val-S 1169 > docs/results/2026-11-30-side-view/compare67-1169.md
echo done > $R/done-1169
