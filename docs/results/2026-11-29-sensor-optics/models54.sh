#!/bin/bash
# Rule 54's candidate Z, its sets and the evaluations (rule54.md), from the repository root; resumable (each step is
# skipped when its output is there). Needs runs/r52/F and rule 53's decision (decide53.md) for the control K.
set -euo pipefail
S=docs/results/2026-11-29-sensor-optics
export PYTHONPATH=. OMP_NUM_THREADS=1
mkdir -p runs/r54
[ -f data/line-pvv-train/samples/000899/params.json ] || .venv/bin/python $S/expose53.py data/line-pv-train \
    data/line-pvv-train $S/lens2-vary.toml --check 2
[ -f data/line-pvv-val/samples/000599/params.json ] || .venv/bin/python $S/expose53.py data/line-pv-val \
    data/line-pvv-val $S/lens2-vary.toml
lane() {  # lane NAME MODEL VAL KIND...: that model's evaluations on seed 1157's sets, in order
    local m=$1 model=$2 val=$3; shift 3
    for k in "$@"; do
        if [ $k = 1157 ]; then
            [ -f runs/r54/eval-$m-1157/eval.md ] || .venv/bin/station eval --model $model \
                --data data/line-panel-heldout-1157 --val-data $val --out runs/r54/eval-$m-1157
        else
            [ -f runs/r54/eval-$m-$k/eval.md ] || .venv/bin/station eval --model $model --data data/so-$k-1157 \
                --val-data $val --no-synthetic --out runs/r54/eval-$m-$k
        fi
    done
}
sets() {  # wait for seed 1157 and expose its three re-exposures
    until [ $(ls data/line-panel-heldout-1157/samples 2>/dev/null | grep -c '^[0-9]*$') = 400 ]; do sleep 20; done
    for k in vignette blur all; do
        [ -f data/so-$k-1157/samples/000399/raw.png ] || \
            .venv/bin/python $S/resensor.py data/line-panel-heldout-1157 data/so-$k-1157 $k
    done
}
(  # the control's branch: K is known once rule 53 is decided
    sets
    until [ -f $S/decide53.md ]; do sleep 20; done
    if grep -q "| no |" $S/decide53.md; then K=runs/r53/X-ref; KVAL=data/line-pv-val
        [ -f $K.json ] || .venv/bin/python -c "import sys; from model.draem.checkpoint import copy_checkpoint; copy_checkpoint(*sys.argv[1:])" model/weights/default $K
    else K=runs/r53/Y; KVAL=data/line-pvb-val; fi
    lane K $K $KVAL 1157 vignette blur all
) &
while pgrep -f "station variation .*line-pvv-train" > /dev/null; do sleep 10; done  # a fit already under way
[ -f runs/r54/Z0.json ] || .venv/bin/station variation --model runs/r52/F/default --refit --data data/line-pvv-train \
    --val-data data/line-pvv-val --decision variation --out runs/r54/Z0
[ -f runs/r54/Z.json ] || .venv/bin/station residual --model runs/r54/Z0 --data data/line-pvv-train \
    --val-data data/line-pvv-val --members 1 --steps 3000 --second-look --out runs/r54/Z
until [ -f data/so-all-1157/samples/000399/raw.png ]; do sleep 20; done
lane Z runs/r54/Z data/line-pvv-val 1157 vignette
until [ -f runs/r54/eval-K-vignette/eval.md ]; do sleep 20; done
.venv/bin/python $S/decide54.py runs/r54/eval-Z-1157 runs/r54/eval-K-1157 runs/r54/eval-Z-vignette \
    runs/r54/eval-K-vignette runs/r54/Z | tee $S/decide54.md
lane Z runs/r54/Z data/line-pvv-val blur all  # reported beside, not decided on
wait
