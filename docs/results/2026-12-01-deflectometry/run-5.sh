#!/usr/bin/env bash
# plan-5.md: the second camera's stripes judged by a detector (WS-F against WS-V) on validation seed 1176.
# Resumable across sessions (renders resume per sample; quadrature.py skips made parts; each later step skips a
# finished output).
set -euo pipefail
cd "$(dirname "$0")/../../.."  # the repository root
D=docs/results/2026-12-01-deflectometry
R=runs/c80s
mkdir -p $R
export OMP_NUM_THREADS=1 PYTHONPATH=.
P=(--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml
   --config sim/presets/panel-vary.toml)
FINISH=(--config sim/presets/finish-vary.toml)
SIDE=(--config sim/presets/side-view.toml)
for ph in base 0 90; do  # base: the side camera's sets themselves (sw-*, with ground truth); 0, 90: the stripes' twins
    S=(--config $D/side-fringe-$ph.toml --no-ground-truth); out=sfr$ph
    [ $ph = base ] && { S=(); out=sw; }
    for half in 0 1; do  # the train split only (sample k % 10 >= 3), as scripts/make-side-model.sh
        (for j in 3 4 5 6 7 8 9; do
            .venv/bin/station render --out data/$out-train "${P[@]}" "${FINISH[@]}" "${SIDE[@]}" "${S[@]}" \
                --count 900 --seed 101 --defects 0.4 --defects-in-train --shard $((j + 10 * half))/20
        done) > $R/render-$out-train-$half.log 2>&1 &
    done
    wait
    for name in pf-val pv-val pv-val-1176; do  # calibration (the finish drawn), thresholds, the reading
        extra=(); [ $name = pf-val ] && extra=("${FINISH[@]}")
        seed=303; [ $name = pv-val-1176 ] && seed=1176
        for k in 0 1; do
            .venv/bin/station render --out data/$out-$name "${P[@]}" "${extra[@]}" "${SIDE[@]}" "${S[@]}" \
                --count 600 --seed $seed --defects 0.4 --validation --shard $k/2 > $R/render-$out-$name-$k.log 2>&1 &
        done
        wait
    done
done
quadrature() {  # SET: data/sfq-SET from the side set and its stripes' twins
    .venv/bin/python $D/quadrature.py data/sw-$1 data/sfr0-$1 data/sfr90-$1 data/sfq-$1 > $R/sfq-$1.log
}
quadrature train & quadrature pf-val & wait
quadrature pv-val & quadrature pv-val-1176 & wait
# station train needs a val split, which the side training set (its train split only) lacks: the container's 2-step
# keep-best reads 60 calibration parts linked in as val samples (indices 10 j + 2). Its networks do not decide
# (station variation's decision: the variation model alone).
C=$R/sfq-container
if [ ! -d $C ]; then
    mkdir -p $C/samples; cp data/sfq-train/manifest.json $C/
    for d in data/sfq-train/samples/*; do ln -sfn "$(realpath "$d")" $C/samples/"$(basename "$d")"; done
    for j in $(seq 0 59); do
        ln -sfn "$(realpath data/sfq-pf-val/samples/"$(printf %06d "$j")")" $C/samples/"$(printf %06d $((10 * j + 2)))"
    done
fi
NET=(--preset fast --fusion fused --batch-size 8 --seed 0 --device cpu --roi band --size 96 --steps 2 --eval-every 2)
judge() {  # NAME PRIORS: the file WS-NAME (a 2-step container, its variation model) and its reading; one core each
    local n=WS-$1 e=$R/eval-1176-WS-$1
    [ -f $R/$n-net/best.json ] || .venv/bin/station train --data $C --priors "$2" "${NET[@]}" \
        --out $R/$n-net > $R/$n-net.log 2>&1
    [ -f $R/$n.json ] || .venv/bin/station variation --model $R/$n-net/best --data data/sfq-train \
        --val-data data/sfq-pf-val --curvature 3 --out $R/$n > $R/$n-fit.log 2>&1
    [ -f $e/scores.csv ] || .venv/bin/station eval --model $R/$n --data data/sfq-pv-val-1176 --split val \
        --val-data data/sfq-pv-val --presence-rule row_contrast --no-synthetic --no-plots --out $e > $e.log 2>&1
}
judge V intensity,dolp,aolp & judge F intensity,dolp,aolp,normal & wait
mkdir -p $D/eval
.venv/bin/python $D/read-2.py $R/eval-1176-WS-V $R/eval-1176-WS-F "side camera, seed 1176" \
    "WS-V, its 1 %" "WS-F, its 1 %" > $D/read-5.md
.venv/bin/python $D/read-3-faces.py $R/eval-1176-WS-V $R/eval-1176-WS-F WS-V WS-F >> $D/read-5.md
for n in WS-V WS-F; do cp $R/eval-1176-$n/eval.md $D/eval/eval-1176-$n.md; done
