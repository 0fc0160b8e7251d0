#!/usr/bin/env bash
# plan.md's read, each fresh set once: A (reference from the first part) against B (from the part nearest the median
# pose), paired, each at its own threshold; run from the repository's root after render.sh.
set -euo pipefail
export OMP_NUM_THREADS=1 PYTHONPATH=.
for set in data/turned-20-1232 data/square-1233 data/turned20-1234; do
    echo "== $set"
    .venv/bin/python docs/results/2026-12-06-fit-size/paired.py runs/pose-1800-A/band-look runs/pose-1800/band-look \
        "$set"
done
