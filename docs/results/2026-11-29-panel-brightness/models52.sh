#!/bin/bash
# Rule 52's candidate X and the four evaluations (rule52.md), after runs/r52/queue52.sh's renders
# (data/line-pv-train, data/line-pv-val, data/line-panel-heldout-1154, data/pb-half-1154). Run from the repository
# root; every step writes its own folder under runs/r52.
set -euo pipefail
S=docs/results/2026-11-29-panel-brightness
mkdir -p runs/r52/F
git show 0f17840^:model/weights/default.pt > runs/r52/F/default.pt     # the networks before rule 47's refit
git show 0f17840^:model/weights/default.json > runs/r52/F/default.json
station variation --model runs/r52/F/default --refit --data data/line-pv-train --val-data data/line-pv-val \
    --decision variation --out runs/r52/X0
station residual --model runs/r52/X0 --data data/line-pv-train --val-data data/line-pv-val --members 1 \
    --steps 3000 --second-look --out runs/r52/X
for m in X C; do
    model=runs/r52/X; val=data/line-pv-val
    if [ $m = C ]; then model=model/weights/default; val=data/line-panel-val; fi
    station eval --model $model --data data/line-panel-heldout-1154 --val-data $val --out runs/r52/eval-$m-1154
    station eval --model $model --data data/pb-half-1154 --val-data $val --no-synthetic --out runs/r52/eval-$m-half
done
PYTHONPATH=. python $S/decide52.py runs/r52/eval-X-1154 runs/r52/eval-C-1154 runs/r52/eval-X-half \
    runs/r52/eval-C-half runs/r52/X | tee $S/decide52.md
