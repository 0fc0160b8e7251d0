#!/bin/sh
# Rule 28's reports (run from the repository root after render-28.sh): rule 24's D and rule 27's F, unchanged, on the
# confirmation set (seed 1129) rendered under each line.
set -e
S=.venv/bin/station
$S eval --model runs/df/D --data data/df-confirm --val-data data/df-dome-val --out runs/df/eval-D-confirm
$S eval --model runs/bf/F --data data/fp-confirm --val-data data/fp-val --out runs/bf/eval-F-confirm
$S compare --paired runs/df/eval-D-confirm runs/bf/eval-F-confirm --out runs/bf/paired-F-confirm
# per type and face, paired SEs (the rule's front-face dents), and the figure
cd docs/results/2026-11-27-bright-field && ../../../.venv/bin/python plot.py ../../../runs/df/eval-D-confirm \
    ../../../data/df-confirm ../../../runs/bf/eval-F-confirm ../../../data/fp-confirm \
    ../2026-11-27-dome-and-panel-confirm.png "D: shipped dome" "F: whole dome + panel"
