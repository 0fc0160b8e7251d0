#!/bin/sh
# Rule 25's models and reports (run from the repository root after render.sh). D is rule 24's (runs/df/D: the
# shipped model refitted on the shipped line's first 400 training parts; its held-out report runs/df/eval-D).
set -e
S=.venv/bin/station
[ -e runs/df/D.json ] || sh docs/results/2026-11-27-dark-field/models.sh
[ -e runs/bf/B.json ] || $S variation --model model/weights/default --refit --data data/bf-train \
    --val-data data/bf-val --out runs/bf/B
$S eval --model runs/bf/B --data data/bf-heldout --val-data data/bf-val --out runs/bf/eval-B
$S compare --paired runs/df/eval-D runs/bf/eval-B --out runs/bf/paired
