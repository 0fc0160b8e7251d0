#!/usr/bin/env bash
# The shipped recipe (scripts/make-model.sh, DECISION=variation, steps 3, 6, 6b, 6b' and 6c) on the GGX training set,
# without the held-out-type looks and the reports (a screen): runs/ggx-900/band-look. Each step resumes or skips when
# its output exists; run from the repository's root.
set -euo pipefail
BIN=.venv/bin
DATA=data/line-ef-train-900-ggx
CAL=data/line-ef-val
R=runs/ggx-900
mkdir -p "$R"
[ -f "$R/band/last.json" ] || OMP_NUM_THREADS=2 "$BIN/station" train --data "$DATA" --priors intensity --preset fast \
    --fusion fused --batch-size 8 --seed 0 --device cpu --roi band --size 96 --steps 30 --eval-every 30 --out "$R/band"
[ -f "$R/band-variation.json" ] || OMP_NUM_THREADS=2 "$BIN/station" variation --model "$R/band/last" --data "$DATA" \
    --val-data "$CAL" --out "$R/band-variation" --decision variation
# one look, alone: two threads (make model trains two looks at once, one thread each)
[ -f "$R/band-look.json" ] || OMP_NUM_THREADS=2 "$BIN/station" residual --model "$R/band-variation" --data "$DATA" \
    --val-data "$CAL" --members 1 --steps 3000 --second-look --out "$R/band-look"
grep -qs '"outline": ' "$R/band-look.json" || "$BIN/station" shape --model "$R/band-look" --data "$DATA" \
    --val-data "$CAL" --out "$R/band-look"
"$BIN/station" threshold --model "$R/band-look" --data data/line-pv-val
