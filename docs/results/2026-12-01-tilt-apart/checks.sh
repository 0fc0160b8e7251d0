#!/usr/bin/env bash
# After the screen: what the dome halves' tilt error is made of (tilt_error.txt). The first 80 parts of the
# validation twins (seed 303) rendered again with the stray lamp off, then also with the plastic matte
# (Mitsuba's diffuse BSDF, its colour as drawn), then also with the belt black (blackbelt.toml), and tilt_error.py
# on each. Resumable (renders resume).
set -euo pipefail
cd "$(dirname "$0")/../../.."  # the repository root
D=docs/results/2026-12-01-tilt-apart
export OMP_NUM_THREADS=1 PYTHONPATH=.
T=(--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml
   --config $D/tilt.toml --config $D/nostray.toml --dome-segments 0,180 --count 80 --seed 303 --defects 0.4
   --validation)
render() {  # OUT, then station render's flags
    local out=$1; shift
    for k in 0 1; do .venv/bin/station render --out "$out" "$@" --shard $k/2 > /dev/null 2>&1 & done
    wait
}
render data/tilt-pv-val-nostray "${T[@]}"
render data/tilt-pv-val-matte "${T[@]}" --materials '{"plastic": {"type": "diffuse"}}'
render data/tilt-pv-val-matte-black "${T[@]}" --config $D/blackbelt.toml --materials '{"plastic": {"type": "diffuse"}}'
{
    .venv/bin/python $D/tilt_error.py 40
    .venv/bin/python $D/tilt_error.py 40 --unpolarized
    .venv/bin/python $D/tilt_error.py 40 --data data/tilt-pv-val-nostray
    .venv/bin/python $D/tilt_error.py 40 --data data/tilt-pv-val-matte
    .venv/bin/python $D/tilt_error.py 40 --data data/tilt-pv-val-matte-black
} > $D/tilt_error.txt
