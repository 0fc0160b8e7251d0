#!/usr/bin/env bash
# stop 96: make model end to end but for its networks (stop 95's, trained with its own commands on the same set),
# held out on seed 1187 (the shipped file's report set), no new-kinds set, not shipped
cd /work/main
SHIP=0 NEW_KINDS_COUNT=0 HELDOUT=data/line-panel-heldout-1187 HELDOUT_SEED=1187 RUNS=runs/make-model-96 \
    scripts/make-model.sh
