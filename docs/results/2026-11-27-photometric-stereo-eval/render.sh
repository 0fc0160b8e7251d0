#!/usr/bin/env bash
# Rule 23 (docs/results/2026-11-27-photometric-stereo-eval.md): the photometric-stereo sets of the station-fixed
# line (dome halves 0 / 180), resumable: rerun to continue. Logs go to runs/ps/.
set -u
cd /work/main
V="--config sim/presets/line-polar.toml --config sim/presets/variation.toml"
N=docs/results/2026-11-25-narrow-lines
F="--config docs/results/2026-11-24-fixed-camera/fixed-camera.toml --config $N/no-stray-light.toml --config $N/fixed-exposure.toml --config docs/results/2026-11-25-gradient-dome/gradient-dome.toml"
S="--dome-segments 0,180"
run() {  # out, args...
  out=$1; shift
  for k in 0 1; do OMP_NUM_THREADS=1 .venv/bin/station render $V $F $S "$@" --shard $k/2 --out $out > runs/ps/$(basename $out)-$k.log 2>&1 & done
  wait
}
run data/ps-train --count 360 --seed 141 --defects 0
run data/ps-val --count 200 --seed 343 --defects 0.4 --validation
run data/ps-heldout --count 400 --seed 545 --defects 0.6 --heldout
echo done > runs/ps/done
