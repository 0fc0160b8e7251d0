#!/usr/bin/env bash
# The stray-lamp twins and the Stokes-units screen (validation sets only). Renders ~4 min, fit ~6 min, scores ~6 min.
set -euo pipefail
D=docs/results/2026-12-01-stokes-units
R=${R:-runs/s74}
PY=${PY:-.venv/bin/python}
export PYTHONPATH=. OMP_NUM_THREADS=1
P="--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml"
for k in 0 1; do  # the first 150 parts of make model's VAL set, without the stray lamp
    .venv/bin/station render --out data/line-pv-val-nostray $P --config sim/presets/panel-vary.toml \
        --config docs/results/2026-11-30-report-1167/no-stray.toml --count 150 --seed 303 --defects 0.4 \
        --validation --shard $k/2 &
done
wait
"$PY" $D/twins.py data/line-pv-val data/line-pv-val-nostray $D/twins.png > $D/twins.txt
# Fv: the shipped variation model fitted again (stop 73: runs/c73/repro, from 0f17840^'s file); Pv: the same with
# (S1, S2) / median S0
[ -f "$R/Pv.json" ] || "$PY" $D/patched.py variation --model runs/c73/repro/src/default --refit \
    --data data/line-pf-train --val-data data/line-pf-val --decision variation --out "$R/Pv"
for s in line-pv-val line-pv-val-1176; do
    .venv/bin/station eval --model runs/c73/repro/Fv --data data/$s --split val --no-synthetic --no-plots \
        --out $D/eval-Fv-$s
    "$PY" $D/patched.py eval --model "$R/Pv" --data data/$s --split val --no-synthetic --no-plots --out $D/eval-Pv-$s
done
"$PY" $D/screen_read.py $D Fv Pv > $D/screen.txt
