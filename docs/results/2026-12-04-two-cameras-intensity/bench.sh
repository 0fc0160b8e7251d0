#!/usr/bin/env bash
# After the reading (no bar): what a part costs with the shipped line file beside the side file, as
# ../2026-11-30-two-camera-station.md measured it with earlier files: the demo's parts and their side twins
# (second-camera.md's command), the loop with virtual cameras, three pair modes in one run. Resumable.
set -euo pipefail
HERE=$(cd "$(dirname "$0")" && pwd)
cd "$HERE/../../.."
export OMP_NUM_THREADS=1
P=(--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml)
for k in 0 1; do
    .venv/bin/station render --out data/sim-demo-side "${P[@]}" --config sim/presets/side-view.toml --count 40 \
        --seed 7 --defects 0.5 --defects-in-train --shard $k/2 > runs/two-cameras-intensity/render-demo-side-$k.log 2>&1 &
done
wait
unset OMP_NUM_THREADS  # the station's own thread settings, as a line runs it
.venv/bin/station bench pipeline --data data/sim-demo-line-panel --methods bilinear --precisions fp32 --presence on \
    --parts 200 --second-model runs/make-side-model/side --second-data data/sim-demo-side \
    --pair-modes first-only,parallel,serial --out runs/two-cameras-intensity/bench
cp runs/two-cameras-intensity/bench/pipeline.md "$HERE/bench.md"
cp runs/two-cameras-intensity/bench/pipeline.json "$HERE/bench.json"
