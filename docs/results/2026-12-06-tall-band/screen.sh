#!/usr/bin/env bash
# The tall band's screen (plan.md): arms B (band, 96) and T (tall, 128), variation-only files made alike. Resumable:
# each step is skipped when its output exists. Run from the repository's root; R holds the files (not in git).
set -euo pipefail
R=${R:-runs/s113/tall}
DATA=data/line-ef-train CAL=data/line-pv-val VAL=data/line-pv-val
S=.venv/bin/station
export OMP_NUM_THREADS=${OMP_NUM_THREADS:-2}
for arm in B:band:96 T:tall:128; do
    IFS=: read -r name roi size <<< "$arm"
    out=$R/$name
    mkdir -p "$out"
    [ -f "$out/shell/last.json" ] || $S train --data $DATA --priors intensity --preset fast --fusion fused \
        --batch-size 8 --seed 0 --device cpu --roi "$roi" --size "$size" --steps 30 --eval-every 30 --out "$out/shell"
    [ -f "$out/var.json" ] || /usr/bin/time -v $S variation --model "$out/shell/last" --data $DATA --val-data $CAL \
        --out "$out/var" --decision variation 2> "$out/variation-time.txt"
    grep -qs '"outline": ' "$out/var.json" || $S shape --model "$out/var" --data $DATA --val-data $CAL --out "$out/var"
    $S threshold --model "$out/var" --data $VAL
done
