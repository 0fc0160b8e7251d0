#!/bin/bash
# After rule 67 shipped E63: the shipped file again on seed 1184's "rendered differently" sets (stop 84's and 85's,
# which measured the file before): by default Mitsuba's spectral variant, 30 pixels stuck at full scale unmapped, the
# part moving 4 px during the exposure, and the frames as a Mono8 camera streams them. KINDS names others (after
# those: KINDS="motion2 pedestal256" and KINDS="dead30 prnu1", one lane each). Resumable.
set -euo pipefail
cd "$(dirname "$0")/../../.."  # the repository root
S=docs/results/2026-12-02-edge-range/others
export PYTHONPATH=. OMP_NUM_THREADS=1
mkdir -p $S
for k in ${KINDS:-spectral hot30 motion4 bit8}; do
  [ -f $S/eval-E63-$k-1184/eval.md ] || .venv/bin/station eval --model model/weights/default \
    --data data/$k-heldout-1184 --val-data data/line-pv-val --no-synthetic --no-plots \
    --out $S/eval-E63-$k-1184 > runs/c86/others-$k.log 2>&1
  rm -f $S/eval-E63-$k-1184/eval.json
done
echo "others done $(date +%T)"
