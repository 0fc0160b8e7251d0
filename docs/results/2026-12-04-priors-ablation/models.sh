#!/usr/bin/env bash
# The priors ablation's models (run from anywhere; resumable: a finished file is kept). Each is make-model.sh's
# steps 6, 6b and 6c with fewer priors: the decision is the variation model and its look network, so the DRAEM
# network under it is a 30-step shell that only carries the priors, the band and the input size (it does not decide).
#   R   intensity
#   RA  intensity and AoLP (read as the unit vector (cos 2a, sin 2a))
#   RAD intensity, DoLP and AoLP (the shipped recipe: AoLP read as (S1, S2) / S0): make model's own file from these
#       sets, runs/make-model-96/band-look (docs/results/2026-12-04-recipe-reproduction.md)
set -euo pipefail
cd "$(dirname "$0")/../../.."
S=.venv/bin/station
RUNS=${RUNS:-runs/abl}
DATA=data/line-ef-train CALIBRATION=data/line-ef-val VAL=data/line-pv-val
export OMP_NUM_THREADS=1
one() {  # one NAME PRIORS
    local name=$1 priors=$2
    [ -e "$RUNS/$name/last.json" ] || $S train --data "$DATA" --priors "$priors" --preset fast --fusion fused \
        --roi band --size 96 --steps 30 --batch-size 8 --eval-every 30 --device cpu --seed 0 --out "$RUNS/$name"
    [ -e "$RUNS/$name-variation.json" ] || $S variation --model "$RUNS/$name/last" --data "$DATA" \
        --val-data "$CALIBRATION" --decision variation --out "$RUNS/$name-variation"
    if [ ! -e "$RUNS/$name-look.json" ]; then
        $S residual --model "$RUNS/$name-variation" --data "$DATA" --val-data "$CALIBRATION" --members 1 \
            --steps 3000 --second-look --out "$RUNS/$name-look"
        $S threshold --model "$RUNS/$name-look" --data "$VAL"
    fi
}
one "${1:-R}" "${2:-intensity}"
