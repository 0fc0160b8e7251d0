#!/bin/bash
# Rule 53's candidate Y and the four evaluations (rule53.md), from the repository root; every step writes its own
# folder under runs/r53 and is skipped when it is there (resumable). Needs runs/r52/F (models52.sh's first lines)
# and data/line-panel-heldout-1156.
set -euo pipefail
S=docs/results/2026-11-29-sensor-optics
export PYTHONPATH=. OMP_NUM_THREADS=1
mkdir -p runs/r53
[ -f data/line-pvb-train/samples/000899/params.json ] || .venv/bin/python $S/expose53.py data/line-pv-train data/line-pvb-train $S/lens-vary.toml
[ -f data/line-pvb-val/samples/000599/params.json ] || .venv/bin/python $S/expose53.py data/line-pv-val data/line-pvb-val $S/lens-vary.toml
[ -f runs/r53/Y0.json ] || .venv/bin/station variation --model runs/r52/F/default --refit --data data/line-pvb-train \
    --val-data data/line-pvb-val --decision variation --out runs/r53/Y0
[ -f runs/r53/Y.json ] || .venv/bin/station residual --model runs/r53/Y0 --data data/line-pvb-train \
    --val-data data/line-pvb-val --members 1 --steps 3000 --second-look --out runs/r53/Y
until [ $(ls data/line-panel-heldout-1156/samples 2>/dev/null | grep -c '^[0-9]*$') = 400 ]; do sleep 20; done
[ -d data/so-blur-1156 ] || .venv/bin/python $S/resensor.py data/line-panel-heldout-1156 data/so-blur-1156 blur
for m in Y X; do
    model=runs/r53/Y; val=data/line-pvb-val
    if [ $m = X ]; then model=model/weights/default; val=data/line-pv-val; fi
    [ -d runs/r53/eval-$m-1156 ] || .venv/bin/station eval --model $model --data data/line-panel-heldout-1156 --val-data $val \
        --out runs/r53/eval-$m-1156
    [ -d runs/r53/eval-$m-blur ] || .venv/bin/station eval --model $model --data data/so-blur-1156 --val-data $val \
        --no-synthetic --out runs/r53/eval-$m-blur
done
.venv/bin/python $S/decide53.py runs/r53/eval-Y-1156 runs/r53/eval-X-1156 runs/r53/eval-Y-blur runs/r53/eval-X-blur \
    runs/r53/Y | tee $S/decide53.md
