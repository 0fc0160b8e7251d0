#!/usr/bin/env bash
# plan-6.md: the stripes judged on the top face only (F-top) beside the shipped file, on a fresh seed (1184) with a
# 1200-part validation set. Resumable (renders resume; quadrature.py skips made parts; each later step skips a
# finished output). RENDER_ONLY=1 stops after the renders.
set -euo pipefail
cd "$(dirname "$0")/../../.."  # the repository root
D=docs/results/2026-12-01-deflectometry
R=runs/c82
mkdir -p $R
export OMP_NUM_THREADS=1 PYTHONPATH=.
P=(--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml)
VARY=(--config sim/presets/panel-vary.toml)
FINISH=(--config sim/presets/finish-vary.toml)
render() {  # OUT, then station render's flags
    local out=$1; shift
    for k in 0 1; do
        .venv/bin/station render --out "$out" "$@" --shard $k/2 > "$R/render-$(basename "$out")-$k.log" 2>&1 &
    done
    wait
}
T=(--count 900 --seed 101 --defects 0.4 --defects-in-train)
V=(--count 1200 --seed 303 --defects 0.4 --validation)
H=(--count 400 --seed 1184 --defects 0.6 --heldout)
render data/line-pf-train "${P[@]}" "${VARY[@]}" "${FINISH[@]}" "${T[@]}"
for ph in 0 90; do
    render data/fr$ph-pf-train "${P[@]}" "${VARY[@]}" "${FINISH[@]}" --config $D/fringe-$ph.toml "${T[@]}" \
        --no-ground-truth
done
render data/line-pv-val-1200 "${P[@]}" "${VARY[@]}" "${V[@]}"
for ph in 0 90; do
    render data/fr$ph-pv-val-1200 "${P[@]}" "${VARY[@]}" --config $D/fringe-$ph.toml "${V[@]}" --no-ground-truth
done
render data/line-panel-heldout-1184 "${P[@]}" "${H[@]}" --visibility
for ph in 0 90; do
    render data/fr$ph-heldout-1184 "${P[@]}" --config $D/fringe-$ph.toml "${H[@]}" --no-ground-truth
done
[ "${RENDER_ONLY:-0}" = 1 ] && exit 0
quadrature() {  # SET: data/fq-SET from the line set and its stripes' twins
    local line=data/line-$1; [ -d "$line" ] || line=data/line-panel-$1
    .venv/bin/python $D/quadrature.py "$line" data/fr0-$1 data/fr90-$1 data/fq-$1 > $R/fq-$1.log
}
quadrature pf-train & quadrature pv-val-1200 & wait
quadrature heldout-1184
export OMP_NUM_THREADS=2
NET=(--preset fast --fusion fused --batch-size 8 --seed 0 --device cpu --roi band --size 96 --steps 2 --eval-every 2)
[ -f $R/F-net/best.json ] || .venv/bin/station train --data data/fq-pf-train --priors intensity,normal \
    "${NET[@]}" --out $R/F-net > $R/F-net.log 2>&1
[ -f $R/F-top.json ] || .venv/bin/station variation --model $R/F-net/best --data data/fq-pf-train \
    --val-data data/fq-pv-val-1200 --curvature 3 --judged-priors normal --out $R/F-top > $R/F-top-fit.log 2>&1
ev() {  # NAME MODEL DATA VAL
    [ -f $R/eval-1184-$1/scores.csv ] || .venv/bin/station eval --model "$2" --data "$3" --val-data "$4" \
        --no-synthetic --no-plots --out $R/eval-1184-$1 > $R/eval-1184-$1.log 2>&1
}
ev shipped model/weights/default data/line-panel-heldout-1184 data/line-pv-val-1200
ev F-top $R/F-top data/fq-heldout-1184 data/fq-pv-val-1200
[ -f $R/split-F-top.json ] || .venv/bin/station split --model model/weights/default --data data/line-pv-val-1200 \
    --second-model $R/F-top --second-data data/fq-pv-val-1200 --second-presence-rule dolp_contrast \
    --out $R/split-F-top.json > $R/split-F-top.log 2>&1
.venv/bin/station compare $R/eval-1184-shipped $R/eval-1184-F-top --split $R/split-F-top.json --out $R/pair-F-top
mkdir -p $D/eval
cp $R/pair-F-top/two-cameras.md $D/eval/pair-1184-F-top.md
cp $R/split-F-top.json $D/eval/split-1184-F-top.json
for n in shipped F-top; do cp $R/eval-1184-$n/eval.md $D/eval/eval-1184-$n.md; done
# beside the reading, not deciding: each file at its own 1 % point, by type and face
.venv/bin/python $D/read-3-faces.py $R/eval-1184-shipped $R/eval-1184-F-top shipped F-top > $D/read-6-faces.md
