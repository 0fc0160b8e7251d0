#!/usr/bin/env bash
# The shipped file (model/weights/default, E63) on the ablation's two fresh sets, as its own report sets are read:
# thresholds from its sidecar (set on data/line-pv-val), held fixed. Run after the ablation (resumable).
set -euo pipefail
cd "$(dirname "$0")"
export OMP_NUM_THREADS=1
for seed in 1191 1192; do
    [ -e "shipped/eval-E63-$seed/scores.csv" ] || ../../../.venv/bin/station eval --model ../../../model/weights/default \
        --data "../../../data/line-heldout-$seed" --val-data ../../../data/line-pv-val --out "shipped/eval-E63-$seed" &
done
wait
