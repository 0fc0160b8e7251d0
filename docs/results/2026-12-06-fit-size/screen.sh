#!/usr/bin/env bash
# plan.md's arms and reading: the shipped file's networks alone, a variation model fitted by station variation (the
# shipped recipe's defaults) on F's first 375 good train parts and on all of them, each read once by station eval on
# T, then paired.py. Resumable (a finished step is kept); run from the repository's root after render.sh.
set -euo pipefail
R=runs/fit-size
mkdir -p "$R"
[ -f "$R/nets.json" ] || .venv/bin/python -c "import sys; from model.draem.checkpoint import load_checkpoint, \
save_checkpoint; from model.draem.with_variation import networks_only; \
save_checkpoint(sys.argv[2], networks_only(load_checkpoint(sys.argv[1]).detector))" model/weights/default "$R/nets"
for n in 375 all; do
    parts=(); [ "$n" = all ] || parts=(--fit-parts "$n")
    [ -f "$R/v$n.json" ] || .venv/bin/station variation --model "$R/nets" --data data/fit-1213 \
        --val-data data/fit-1215-val --decision variation "${parts[@]}" --out "$R/v$n"
done
for n in 375 all; do
    [ -f "$R/eval-$n/eval.json" ] || .venv/bin/station eval --model "$R/v$n" --data data/fit-1214-test \
        --val-data data/fit-1215-val --no-synthetic --out "$R/eval-$n"
done
.venv/bin/python docs/results/2026-12-06-fit-size/paired.py "$R/v375" "$R/vall" data/fit-1214-test
