#!/bin/sh
# Rules 30-31, step 2 (run from the repository root after render.sh with STEP=2): the shipped recipe on each line,
# on the same parts. P: the shipped line, its sets' first 400 (seed 101) and 300 (seed 303) samples linked into
# data/fl-train-P and data/fl-val-P; Q: the front light's sets. Both refit the shipped model's variation model.
set -e
S=.venv/bin/station
R=docs/results/2026-11-27-front-light
for pair in "line-panel-train fl-train-P 400" "line-panel-val fl-val-P 300"; do
    set -- $pair
    mkdir -p data/$2/samples && cp data/$1/manifest.json data/$2/
    for i in $(seq 0 $(($3 - 1))); do d=$(printf %06d $i); ln -sfn "$(realpath data/$1/samples/$d)" data/$2/samples/$d; done
done
fit() {  # NAME TRAIN VAL HELDOUT
    [ -f runs/fl/$1.json ] || $S variation --model model/weights/default --refit --data data/$2 --val-data data/$3 \
        --decision variation --out runs/fl/$1
    [ -f $R/eval-$1/eval.json ] || $S eval --model runs/fl/$1 --data data/$4 --val-data data/$3 --out $R/eval-$1
}
fit P fl-train-P fl-val-P line-panel-heldout-1131
fit Q fl-train fl-val fl-heldout
$S compare --paired $R/eval-P $R/eval-Q --out $R/paired
.venv/bin/python $R/groups.py $R/eval-P data/line-panel-heldout-1131 $R/eval-Q data/fl-heldout $R/groups.json
# per type and face, paired SEs, and the figure (rule 25's plot.py; it writes faces-eval-Q.json beside itself)
cd docs/results/2026-11-27-bright-field && ../../../.venv/bin/python plot.py ../../../$R/eval-P \
    ../../../data/line-panel-heldout-1131 ../../../$R/eval-Q ../../../data/fl-heldout \
    ../2026-11-27-front-light.png "P: shipped line" "Q: + front light" > ../../../$R/faces.md
mv faces-eval-Q.json ../../../$R/faces.json
