#!/usr/bin/env bash
# plan-3.md: the fresh-seed check of RADF against RAD on seed 1183 (held out; never rendered before). Resumable
# (renders resume; quadrature.py skips made parts; each later step skips a finished output). Needs run.sh's sets
# (data/line-pf-train, fq-pf-train, fq-pv-val; quadrature.py remakes the fq-* sets from data/fr*).
set -euo pipefail
cd "$(dirname "$0")/../../.."  # the repository root
D=docs/results/2026-12-01-deflectometry
R=runs/c80
mkdir -p $R
export OMP_NUM_THREADS=1 PYTHONPATH=.
P=(--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml)
VARY=(--config sim/presets/panel-vary.toml --config sim/presets/finish-vary.toml)
render() {  # OUT, then station render's flags
    local out=$1; shift
    for k in 0 1; do
        .venv/bin/station render --out "$out" "$@" --shard $k/2 > "$R/render-$(basename "$out")-$k.log" 2>&1 &
    done
    wait
}
H=(--count 400 --seed 1183 --defects 0.6 --heldout)
render data/line-panel-heldout-1183 "${P[@]}" "${H[@]}" --visibility
for ph in 0 90; do
    render data/fr$ph-heldout-1183 "${P[@]}" --config $D/fringe-$ph.toml "${H[@]}" --no-ground-truth
done
for ph in 0 90; do
    render data/fr$ph-pf-val "${P[@]}" "${VARY[@]}" --config $D/fringe-$ph.toml --count 600 --seed 303 \
        --defects 0.4 --validation --no-ground-truth
done
quadrature() {  # SET: data/fq-SET from the line set and its stripes' twins
    local line=data/line-$1; [ -d "$line" ] || line=data/line-panel-$1
    .venv/bin/python $D/quadrature.py "$line" data/fr0-$1 data/fr90-$1 data/fq-$1 > $R/fq-$1.log
}
quadrature pf-train & quadrature pv-val & wait
quadrature pf-val & quadrature heldout-1183 & wait
export OMP_NUM_THREADS=2
[ -f $R/RADF-c.json ] || .venv/bin/station variation --model runs/c79/RADF-net/best --data data/fq-pf-train \
    --val-data data/fq-pf-val --curvature 3 --out $R/RADF-c > $R/RADF-c-fit.log 2>&1
ev() {  # NAME MODEL DATA VAL
    [ -f $R/eval-1183-$1/scores.csv ] || .venv/bin/station eval --model "$2" --data "$3" --val-data "$4" \
        --no-synthetic --no-plots --out $R/eval-1183-$1 > $R/eval-1183-$1.log 2>&1
}
ev RAD runs/c76/V1 data/line-panel-heldout-1183 data/line-pv-val
ev RADF-c $R/RADF-c data/fq-heldout-1183 data/fq-pv-val
ev RADF runs/c79/RADF data/fq-heldout-1183 data/fq-pv-val
mkdir -p $D/eval
.venv/bin/python $D/read-2.py $R/eval-1183-RAD $R/eval-1183-RADF-c "seed 1183" > $D/read-3.md
.venv/bin/python $D/read-2.py $R/eval-1183-RAD $R/eval-1183-RADF "seed 1183" >> $D/read-3.md
for n in RAD RADF-c RADF; do cp $R/eval-1183-$n/eval.md $D/eval/eval-1183-$n.md; done
ev shipped model/weights/default data/line-panel-heldout-1183 data/line-pv-val
cp $R/eval-1183-shipped/eval.md $D/eval/eval-1183-shipped.md
