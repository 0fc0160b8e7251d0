#!/bin/sh
# Rule 29's models and reports (run from the repository root; the sets are make-model.sh's and rule 28's).
set -e
S=.venv/bin/station
for P in R:intensity RA:intensity,aolp; do
    name=${P%%:*}; priors=${P#*:}
    [ -e runs/pp/$name/last.json ] || $S train --data data/line-panel-train --priors $priors --preset fast \
        --fusion fused --roi band --size 96 --steps 30 --batch-size 8 --eval-every 30 --device cpu --seed 0 \
        --out runs/pp/$name
    [ -e runs/pp/$name-var.json ] || $S variation --model runs/pp/$name/last --data data/line-panel-train \
        --val-data data/line-panel-val --decision variation --out runs/pp/$name-var
done
for M in R:runs/pp/R-var RA:runs/pp/RA-var RAD:model/weights/default; do
    name=${M%%:*}; model=${M#*:}
    [ -e runs/pp/eval-$name-1130/eval.json ] || $S eval --model $model --data data/line-panel-heldout \
        --val-data data/line-panel-val --out runs/pp/eval-$name-1130
    [ -e runs/pp/eval-$name-1129/eval.json ] || $S eval --model $model --data data/fp-confirm \
        --val-data data/line-panel-val --out runs/pp/eval-$name-1129
done
B=docs/results/2026-11-27-bright-field
for s in 1130 1129; do
    data=data/line-panel-heldout; [ $s = 1129 ] && data=data/fp-confirm
    $S compare --paired runs/pp/eval-R-$s runs/pp/eval-RA-$s runs/pp/eval-RAD-$s --out runs/pp/paired-$s
    $S compare --paired runs/pp/eval-RA-$s runs/pp/eval-RAD-$s --out runs/pp/paired-RA-$s
    # per type and face, RAD against R (paired SEs), and the figure
    (cd $B && ../../../.venv/bin/python plot.py ../../../runs/pp/eval-R-$s ../../../$data \
        ../../../runs/pp/eval-RAD-$s ../../../$data ../2026-11-27-panel-priors/faces-$s.png \
        "R: intensity" "RAD: intensity, DoLP, AoLP")
    mv $B/faces-eval-RAD-$s.json docs/results/2026-11-27-panel-priors/
done
