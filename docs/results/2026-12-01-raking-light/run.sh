#!/usr/bin/env bash
# plan.md: the raking light's screen on validation sets. Resumable (renders resume; each step skips a finished
# output). About 45 min of renders on 2 cores, then the fit and the evaluations.
set -euo pipefail
cd "$(dirname "$0")/../../.."  # the repository root
D=docs/results/2026-12-01-raking-light
R=runs/c77
mkdir -p $R
export OMP_NUM_THREADS=1
K=(--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config $D/raking.toml)
NEW=docs/results/2026-12-01-new-kinds/types.toml
render() {  # OUT, then station render's flags
    local out=$1; shift
    for k in 0 1; do
        .venv/bin/station render --out "$out" "${K[@]}" "$@" --shard $k/2 > "$R/render-$(basename "$out")-$k.log" 2>&1 &
    done
    wait
}
render data/raking-train --count 540 --seed 101 --defects 0
render data/raking-pv-val --count 600 --seed 303 --defects 0.4 --validation
render data/raking-new-kinds-val-1180 --config $NEW --count 400 --seed 1180 --defects 0.6 --validation
export OMP_NUM_THREADS=2
NET=(--priors intensity,dolp,aolp --preset fast --fusion fused --batch-size 8 --seed 0 --device cpu --roi band
     --size 96 --steps 2 --eval-every 2)
[ -f $R/K-net/best.json ] || .venv/bin/station train --data data/raking-train "${NET[@]}" --out $R/K-net > $R/K-net.log 2>&1
[ -f $R/K.json ] || .venv/bin/station variation --model $R/K-net/best --data data/raking-train \
    --val-data data/raking-pv-val --curvature 3 --out $R/K > $R/K-fit.log 2>&1
[ -f $R/eval-S-new/scores.csv ] || .venv/bin/station eval --model model/weights/default \
    --data data/new-kinds-val-1180 --split val --val-data data/line-pv-val --no-synthetic --no-plots \
    --out $R/eval-S-new > $R/eval-S-new.log 2>&1
[ -f $R/eval-K-new/scores.csv ] || .venv/bin/station eval --model $R/K --data data/raking-new-kinds-val-1180 \
    --split val --val-data data/raking-pv-val --presence-rule "${PRESENCE:-row_contrast}" --no-synthetic --no-plots \
    --out $R/eval-K-new > $R/eval-K-new.log 2>&1
[ -f $R/eval-K-val/scores.csv ] || .venv/bin/station eval --model $R/K --data data/raking-pv-val --split val \
    --val-data data/raking-pv-val --presence-rule "${PRESENCE:-row_contrast}" --no-synthetic --no-plots \
    --out $R/eval-K-val > $R/eval-K-val.log 2>&1
[ -f $R/split-K.json ] || .venv/bin/station split --model model/weights/default --data data/line-pv-val \
    --second-model $R/K --second-data data/raking-pv-val --second-presence-rule "${PRESENCE:-row_contrast}" \
    --out $R/split-K.json > $R/split-K.log 2>&1
.venv/bin/station compare $R/eval-S-new $R/eval-K-new --split $R/split-K.json --out $R/pair-new
mkdir -p $D/eval
cp $R/pair-new/* $D/eval/
cp $R/eval-S-new/eval.md $D/eval/eval-S-new.md
cp $R/eval-K-new/eval.md $D/eval/eval-K-new.md
cp $R/eval-K-val/eval.md $D/eval/eval-K-val.md
cp $R/split-K.json $D/eval/
