#!/usr/bin/env bash
# plan.md's addendum 2: candidate Q and the control R, made from nothing on this machine (the earlier machine's sets
# and runs did not survive). Both are `make model` as shipped but for SMOOTH_FIELD; no held-out-type looks and no
# new-kinds set (the plan's reads need neither; a shipped Q would be remade with them), its own report set seed 1194
# as the earlier Q's but 150 parts (the bars are read on the fresh sets). R starts once Q's renders are done and
# shares them (the same paths: render resumes); the two then train side by side (each look network on one thread).
# Resumable; at nice 19 (autogroup), beside run.sh.
set -euo pipefail
cd "$(dirname "$0")/../../.."
echo 19 > /proc/self/autogroup 2>/dev/null || true  # nice across sessions: Linux autogroups ignore a process's own nice
export SHIP=0 HOLDOUT_TYPES=" " NEW_KINDS_COUNT=0 HELDOUT=data/line-heldout-1194 HELDOUT_SEED=1194 HELDOUT_COUNT=150
seen=$(cat runs/make-model-sf/timings.tsv 2>/dev/null | wc -l)  # a rerun: wait for this run's lines, not the last's
SMOOTH_FIELD=1 RUNS=runs/make-model-sf scripts/make-model.sh & q=$!
until tail -n "+$((seen + 1))" runs/make-model-sf/timings.tsv 2>/dev/null | grep -q "render	data/line-pv-val"; do
    sleep 30  # Q's last render (resumed: done at once)
done
SMOOTH_FIELD=0 RUNS=runs/make-model-r scripts/make-model.sh
wait "$q"
