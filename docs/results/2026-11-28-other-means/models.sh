#!/bin/sh
# Rule 35, after render.sh (run from the repository root; each evaluation is skipped when its report exists):
# the shipped model on S (data/line-panel-heldout-1133), G, E and R (rule 36), thresholds from data/line-panel-val (the shipped
# model's validation set, rendered again as scripts/make-model.sh renders it), then the paired comparison and the
# reading at the shipped threshold.
set -e
S=.venv/bin/station
D=docs/results/2026-11-28-other-means
for x in S:line-panel-heldout-1133 G:om-ggx E:om-ior R:om-rough; do
    name=${x%%:*}; data=${x#*:}
    [ -f $D/eval-$name/eval.json ] || $S eval --model model/weights/default --data data/$data \
        --val-data data/line-panel-val --out $D/eval-$name
done
$S compare --paired $D/eval-S $D/eval-G $D/eval-E $D/eval-R --out $D/paired
PYTHONPATH=. .venv/bin/python $D/analysis.py model/weights/default $D/threshold \
    S=$D/eval-S:data/line-panel-heldout-1133 G=$D/eval-G:data/om-ggx E=$D/eval-E:data/om-ior \
    R=$D/eval-R:data/om-rough > $D/threshold.md
mv $D/threshold.png docs/results/2026-11-28-other-means.png
