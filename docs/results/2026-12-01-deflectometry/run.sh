#!/usr/bin/env bash
# plan.md: the deflectometry frames' phase judged on its own (F), joined with RAD (runs/c76/V1) at rule 64's split;
# validation only. Resumable (renders resume; quadrature.py skips made parts; each later step skips a finished
# output). About 4200 frames of renders on 2 cores, then the fit and the evaluations.
set -euo pipefail
cd "$(dirname "$0")/../../.."  # the repository root
D=docs/results/2026-12-01-deflectometry
R=runs/c79
mkdir -p $R
export OMP_NUM_THREADS=1 PYTHONPATH=.
P=(--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml
   --config sim/presets/panel-vary.toml)
render() {  # OUT, then station render's flags
    local out=$1; shift
    for k in 0 1; do
        .venv/bin/station render --out "$out" "$@" --no-ground-truth --shard $k/2 \
            > "$R/render-$(basename "$out")-$k.log" 2>&1 &
    done
    wait
}
for ph in 0 90; do
    render data/fr$ph-pf-train "${P[@]}" --config sim/presets/finish-vary.toml --config $D/fringe-$ph.toml \
        --count 900 --seed 101 --defects 0.4 --defects-in-train
done
for ph in 0 90; do
    render data/fr$ph-pv-val "${P[@]}" --config $D/fringe-$ph.toml --count 600 --seed 303 --defects 0.4 --validation
done
for ph in 0 90; do
    render data/fr$ph-pv-val-1176 "${P[@]}" --config $D/fringe-$ph.toml --count 600 --seed 1176 --defects 0.4 \
        --validation
done
for s in pf-train pv-val pv-val-1176; do
    .venv/bin/python $D/quadrature.py data/line-$s data/fr0-$s data/fr90-$s data/fq-$s > $R/fq-$s.log
done
export OMP_NUM_THREADS=2
NET=(--preset fast --fusion fused --batch-size 8 --seed 0 --device cpu --roi band --size 96 --steps 2 --eval-every 2)
[ -f $R/F-net/best.json ] || .venv/bin/station train --data data/fq-pf-train --priors intensity,normal \
    "${NET[@]}" --out $R/F-net > $R/F-net.log 2>&1
[ -f $R/F.json ] || .venv/bin/station variation --model $R/F-net/best --data data/fq-pf-train \
    --val-data data/fq-pv-val --curvature 3 --out $R/F > $R/F-fit.log 2>&1
e=$R/eval-1176-F
[ -f $e/scores.csv ] || .venv/bin/station eval --model $R/F --data data/fq-pv-val-1176 --split val \
    --val-data data/fq-pv-val --no-synthetic --no-plots --out $e > $e.log 2>&1
[ -f $R/split-F.json ] || .venv/bin/station split --model runs/c76/V1 --data data/line-pv-val \
    --second-model $R/F --second-data data/fq-pv-val --second-presence-rule dolp_contrast \
    --out $R/split-F.json > $R/split-F.log 2>&1
.venv/bin/station compare runs/c77/eval-1176-V1 $e --split $R/split-F.json --out $R/pair-F
mkdir -p $D/eval
cp $R/pair-F/* $R/split-F.json $D/eval/
cp $e/eval.md $D/eval/eval-1176-F.md
.venv/bin/python docs/results/2026-12-01-tilt-apart/read.py runs/c77/eval-1176-V1 "F=$e:$R/split-F.json" \
    "IN-G=runs/c77/eval-1176-ING:runs/c77/split-ING.json" "T=runs/c78/eval-1176-T:runs/c78/split-T.json" \
    > $D/read.md
.venv/bin/python $D/precision.py data/fq-pv-val data/line-pv-val 40 > $D/precision.txt
.venv/bin/python $D/precision.py data/fq-pf-train data/line-pf-train 40 >> $D/precision.txt  # run by hand on 2026-12-01
