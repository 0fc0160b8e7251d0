#!/usr/bin/env bash
# The study (plan.md), resumable: the recipe's sets (train-sets.sh), the fit R, seed 1193 rendered three ways, and
# R and the shipped file E63 scored on each. Run from anywhere.
set -euo pipefail
HERE=$(cd "$(dirname "$0")" && pwd)
cd "$HERE/../../.."
S=.venv/bin/station
export OMP_NUM_THREADS=1
"$HERE/train-sets.sh"
RUNS=runs/ir docs/results/2026-12-04-priors-ablation/models.sh R intensity & fit=$!
V=(--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml
   --count 400 --seed 1193 --defects 0.3 --heldout)
GGX='{"plastic": {"type": "pplastic", "finish": "smooth", "distribution": "ggx"}}'
$S render --out data/ir-built-1193 "${V[@]}"
$S render --out data/ir-ggx-1193 "${V[@]}" --materials "$GGX" & a=$!
$S render --out data/ir-rough-1193 "${V[@]}" --config docs/results/2026-11-28-other-means/rough.toml & b=$!
wait $a; wait $b; wait $fit
for set in built ggx rough; do
    for m in R:runs/ir/R-look E63:model/weights/default; do
        name=${m%%:*}
        [ -e "$HERE/eval/$name-$set/scores.csv" ] || $S eval --model "${m#*:}" --data "data/ir-$set-1193" \
            --val-data data/line-pv-val --no-synthetic --out "$HERE/eval/$name-$set" &
    done
    wait
done
PYTHONPATH=. .venv/bin/python "$HERE/read.py" > "$HERE/read.txt"
PYTHONPATH=. .venv/bin/python "$HERE/plot.py"
