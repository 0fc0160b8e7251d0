#!/usr/bin/env bash
# stop 96: make model end to end but for its networks: stop 95's (../2026-12-04-network-time/run.sh, the recipe's
# own commands on the same set) are copied into the run folder, where make model resumes them; held out on seed 1187
# (the shipped file's report set), no new-kinds set, not shipped. Run from anywhere; resumable.
set -euo pipefail
cd "$(dirname "$0")/../../.."
RUNS=runs/make-model-96
mkdir -p "$RUNS"
for n in base mixed band; do [ -d "$RUNS/$n" ] || cp -r "runs/network-time/$n" "$RUNS/"; done
SHIP=0 NEW_KINDS_COUNT=0 HELDOUT=data/line-panel-heldout-1187 HELDOUT_SEED=1187 RUNS=$RUNS scripts/make-model.sh
