#!/usr/bin/env bash
# The ablation's two held-out sets (resumable), as make-model.sh renders its held-out set: the line as built.
set -euo pipefail
cd "$(dirname "$0")/../../.."
export OMP_NUM_THREADS=1
for seed in ${SEEDS:-1191 1192}; do
    .venv/bin/station render --out "data/line-heldout-$seed" --config sim/presets/line-polar.toml \
        --config sim/presets/variation.toml --config sim/presets/panel.toml --count 400 --seed "$seed" \
        --defects 0.6 --heldout --visibility
done
