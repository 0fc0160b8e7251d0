#!/usr/bin/env bash
# plan.md's reading 3 (after the readings, no bar): what a part costs with the shipped line file beside SA and beside
# SI, as the two-cameras study measured SA (its bench.sh): the demo's parts and their side twins (data/sim-demo-side,
# rendered by that script), the loop with virtual cameras, 200 parts per mode; the two runs back to back on an
# otherwise idle machine, each with its own first-camera-alone peer.
set -euo pipefail
HERE=$(cd "$(dirname "$0")" && pwd)
cd "$HERE/../../.."
for f in SA:runs/make-side-model/side SI:runs/side-intensity/side; do
    .venv/bin/station bench pipeline --data data/sim-demo-line-panel --methods bilinear --precisions fp32 --presence on \
        --parts 200 --second-model "${f#*:}" --second-data data/sim-demo-side \
        --pair-modes first-only,parallel,serial --out "runs/side-intensity/bench-${f%%:*}"
    cp "runs/side-intensity/bench-${f%%:*}/pipeline.md" "$HERE/bench-${f%%:*}.md"
    cp "runs/side-intensity/bench-${f%%:*}/pipeline.json" "$HERE/bench-${f%%:*}.json"
done
