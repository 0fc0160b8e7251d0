#!/usr/bin/env bash
# Seed 1184's 400 parts rendered again by the spectral variant (plan.md), two shards at once; resumable.
set -euo pipefail
cd "$(dirname "$0")/../../.."  # the repository root
export OMP_NUM_THREADS=1 POLAR_ANO_MI_VARIANT=scalar_spectral_polarized
P=(--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml)
mkdir -p runs/c84
for k in 0 1; do
  .venv/bin/station render --out data/spectral-heldout-1184 "${P[@]}" --count 400 --seed 1184 --defects 0.6 \
      --heldout --shard $k/2 > runs/c84/render-spec-$k.log 2>&1 &
done
wait
.venv/bin/station eval --model model/weights/default --data data/spectral-heldout-1184 --val-data data/line-pv-val \
    --out runs/c84/eval-spectral-1184
