#!/usr/bin/env bash
# plan.md's read: A (the shipped file) against B on each fresh set, once; run from the repository's root.
set -euo pipefail
export OMP_NUM_THREADS=1 PYTHONPATH=.
for set in data/square-1236 data/turned20-1237; do
    .venv/bin/python docs/results/2026-12-07-matched-rates/curves.py model/weights/default runs/pose-900/band-look "$set"
done
