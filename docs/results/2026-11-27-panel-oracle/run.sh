#!/bin/sh
# The localised oracle of 2026-11-25-physical-anomalies.md, section 4, for the shipped panel-line model on its two
# held-out sets (run from the repository root; about 10 min per cache on the 2 cores).
set -e
export OMP_NUM_THREADS=2
C=docs/results/2026-11-25-residual-networks/cache.py
O=docs/results/2026-11-25-physical-anomalies/oracle.py
[ -e runs/s43/zcache1130.npz ] || .venv/bin/python $C data/line-panel-train data/line-panel-val \
    data/line-panel-heldout runs/s43/zcache1130.npz
[ -e runs/s43/zcache1129.npz ] || .venv/bin/python $C data/line-panel-train data/line-panel-val \
    data/fp-confirm runs/s43/zcache1129.npz
ORACLE_VAL_CACHE=runs/s43/zcache1130.npz .venv/bin/python $O docs/results/2026-11-27-panel-oracle/oracle.json \
    "1130=data/line-panel-heldout:runs/s43/zcache1130.npz" "1129=data/fp-confirm:runs/s43/zcache1129.npz"
