#!/usr/bin/env bash
# The screen from the committed scripts (validation sets only; data as `make model` renders them). ~3 min.
set -euo pipefail
D=docs/results/2026-12-01-aolp-top-face
PY=${PY:-.venv/bin/python}
export PYTHONPATH=.
"$PY" $D/top_prior.py data/line-pf-train
PRIOR=-1 EDGE=0 "$PY" $D/aolp_screen.py data/line-pv-val $D/val303-A.json
GT=1 PRIOR=-1 EDGE=0 "$PY" $D/aolp_screen.py data/line-pv-val $D/val303-gt.json
PRIOR=0.5 EDGE=0 "$PY" $D/aolp_screen.py data/line-pv-val $D/val303-prior.json
PRIOR=0.5 EDGE=0.05 "$PY" $D/aolp_screen.py data/line-pv-val $D/val303-prior-edge0.05.json
PRIOR=0.5 EDGE=0.1 "$PY" $D/aolp_screen.py data/line-pv-val $D/val303-prior-edge0.1.json
PRIOR=0.5 "$PY" $D/perplace.py data/line-pf-train data/line-pv-val $D/val303-perplace.json
for f in A gt prior prior-edge0.05 prior-edge0.1; do
    echo "== $f"; "$PY" $D/read.py $D/val303-$f.json $D/shipped-val303-scores.csv s5.0
done > $D/screen.txt
echo "== perplace" >> $D/screen.txt
"$PY" $D/read.py $D/val303-perplace.json $D/shipped-val303-scores.csv sP >> $D/screen.txt
PRIOR=-1 EDGE=0 "$PY" $D/figures.py dents data/line-pv-val $D/dents.png
PRIOR=-1 EDGE=0 "$PY" $D/figures.py zmaps data/line-pv-val $D/zmaps.png 000457 000084 000542 000367 000396 000073
