#!/bin/sh
# Rule 27's model and reports (run from the repository root after render-27.sh). D is rule 24's (runs/df/D,
# runs/df/eval-D; docs/results/2026-11-27-dark-field/models.sh makes them).
set -e
S=.venv/bin/station
[ -e runs/bf/F.json ] || $S variation --model model/weights/default --refit --data data/fp-train \
    --val-data data/fp-val --out runs/bf/F
$S eval --model runs/bf/F --data data/fp-heldout --val-data data/fp-val --out runs/bf/eval-F
$S compare --paired runs/df/eval-D runs/bf/eval-F --out runs/bf/paired-F
# per type and face, paired SEs (the rule's front-face dents), and the figure
cd docs/results/2026-11-27-bright-field && ../../../.venv/bin/python plot.py ../../../runs/df/eval-D \
    ../../../data/df-dome-heldout ../../../runs/bf/eval-F ../../../data/fp-heldout ../2026-11-27-dome-and-panel.png \
    "D: shipped dome" "F: whole dome + panel"
