#!/usr/bin/env bash
# plan.md: RAD (runs/c76/V1) against + the learned normal prior (RADN) and + the renderer's normals (RADN-G), on
# a fresh held-out seed 1182. Resumable: renders resume, each step skips a finished output.
set -euo pipefail
cd "$(dirname "$0")/../../.."  # the repository root
D=docs/results/2026-12-01-normal-prior
R=runs/c77
mkdir -p $R
export OMP_NUM_THREADS=1
P=(--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml)
for k in 0 1; do
    .venv/bin/station render --out data/line-panel-heldout-1182 "${P[@]}" --count 400 --seed 1182 --defects 0.6 \
        --heldout --shard $k/2 > $R/render-1182-$k.log 2>&1 &
done
[ -f $R/normals/normal_net.json ] || .venv/bin/station normals --data data/line-pf-train --train-minutes 12 \
    --threads 1 --device cpu --no-plots --out $R/normals > $R/normals.log 2>&1
wait
export OMP_NUM_THREADS=2
NET=(--preset fast --fusion fused --batch-size 8 --seed 0 --device cpu --roi band --size 96 --steps 2 --eval-every 2)
[ -f $R/RADN-net/best.json ] || .venv/bin/station train --data data/line-pf-train --priors intensity,dolp,aolp,normal \
    --normal-net $R/normals/normal_net "${NET[@]}" --out $R/RADN-net > $R/RADN-net.log 2>&1
[ -f $R/RADNG-net/best.json ] || .venv/bin/station train --data data/line-pf-train --priors intensity,dolp,aolp,normal \
    "${NET[@]}" --out $R/RADNG-net > $R/RADNG-net.log 2>&1
for m in RADN RADNG; do
    [ -f $R/$m.json ] || .venv/bin/station variation --model $R/$m-net/best --data data/line-pf-train \
        --val-data data/line-pf-val --curvature 3 --out $R/$m > $R/$m-fit.log 2>&1
done
for m in c76/V1 c77/RADN c77/RADNG; do
    e=$R/eval-1182-$(basename $m)
    [ -f $e/scores.csv ] || .venv/bin/station eval --model runs/$m --data data/line-panel-heldout-1182 \
        --val-data data/line-pv-val --no-synthetic --no-plots --out $e > $e.log 2>&1
done
.venv/bin/station compare --paired $R/eval-1182-V1 $R/eval-1182-RADN $R/eval-1182-RADNG --out $R/compare-normal
mkdir -p $D/eval
cp $R/compare-normal/* $D/eval/
for m in V1 RADN RADNG; do cp $R/eval-1182-$m/eval.md $D/eval/eval-$m.md; done
