#!/usr/bin/env bash
# plan.md: the tilt along x (photometric stereo, panel off) judged on its own, joined with RAD (runs/c76/V1) at rule
# 64's split; validation only. Resumable (renders resume; each later step skips a finished output). About 45 min of
# renders on 2 cores, then the fit and the evaluations.
set -euo pipefail
cd "$(dirname "$0")/../../.."  # the repository root
D=docs/results/2026-12-01-tilt-apart
R=runs/c78
mkdir -p $R
export OMP_NUM_THREADS=1
T=(--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml)
L=(--config $D/tilt.toml --dome-segments 0,180)
render() {  # OUT, then station render's flags
    local out=$1; shift
    for k in 0 1; do
        .venv/bin/station render --out "$out" "$@" --shard $k/2 > "$R/render-$(basename "$out")-$k.log" 2>&1 &
    done
    wait
}
render data/tilt-train "${T[@]}" --config sim/presets/finish-vary.toml "${L[@]}" --count 540 --seed 101 --defects 0
render data/tilt-pv-val "${T[@]}" "${L[@]}" --count 600 --seed 303 --defects 0.4 --validation
render data/tilt-pv-val-1176 "${T[@]}" "${L[@]}" --count 600 --seed 1176 --defects 0.4 --validation
export OMP_NUM_THREADS=2
NET=(--preset fast --fusion fused --batch-size 8 --seed 0 --device cpu --roi band --size 96 --steps 2 --eval-every 2)
[ -f $R/T-net/best.json ] || .venv/bin/station train --data data/tilt-train --priors intensity,tilt_x \
    "${NET[@]}" --out $R/T-net > $R/T-net.log 2>&1
[ -f $R/T.json ] || .venv/bin/station variation --model $R/T-net/best --data data/tilt-train \
    --val-data data/tilt-pv-val --curvature 3 --out $R/T > $R/T-fit.log 2>&1
e=$R/eval-1176-T
[ -f $e/scores.csv ] || .venv/bin/station eval --model $R/T --data data/tilt-pv-val-1176 --split val \
    --val-data data/tilt-pv-val --no-synthetic --no-plots --out $e > $e.log 2>&1
[ -f $R/split-T.json ] || .venv/bin/station split --model runs/c76/V1 --data data/line-pv-val \
    --second-model $R/T --second-data data/tilt-pv-val --second-presence-rule dolp_contrast \
    --out $R/split-T.json > $R/split-T.log 2>&1
.venv/bin/station compare runs/c77/eval-1176-V1 $e --split $R/split-T.json --out $R/pair-T
mkdir -p $D/eval
cp $R/pair-T/* $R/split-T.json $D/eval/
cp $e/eval.md $D/eval/eval-1176-T.md
.venv/bin/python $D/read.py runs/c77/eval-1176-V1 "T=$e:$R/split-T.json" \
    "IN-G=runs/c77/eval-1176-ING:runs/c77/split-ING.json" > $D/read.md
