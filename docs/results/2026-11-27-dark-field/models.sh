#!/bin/sh
# Rule 24's models and reports (run from the repository root after render.sh).
# D: the shipped model refitted on the shipped line's first 400 training parts (data/df-dome-train: links to the
# first 400 samples of data/line-polar-train, seed 101; data/df-dome-val: the first 150 of data/line-polar-val).
set -e
S=.venv/bin/station
[ -e runs/df/D.json ] || $S variation --model model/weights/default --refit --data data/df-dome-train \
    --val-data data/df-dome-val --out runs/df/D
[ -e runs/df/R.json ] || $S variation --model model/weights/default --refit --data data/df-ring-train \
    --val-data data/df-ring-val --out runs/df/R
$S eval --model runs/df/D --data data/df-dome-heldout --val-data data/df-dome-val --out runs/df/eval-D
$S eval --model runs/df/R --data data/df-ring-heldout --val-data data/df-ring-val --out runs/df/eval-R
$S compare --paired runs/df/eval-D runs/df/eval-R --out runs/df/paired
