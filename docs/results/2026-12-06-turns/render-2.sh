#!/usr/bin/env bash
# plan-2.md's set T12: seed 1221, 300 parts, 40 % defective, every part test, the camera turned 12 degrees, rendered
# as plan 1's sets are (render.sh). Resumable, two shards; run from the repository's root.
set -euo pipefail
exec docs/results/2026-12-06-turns/render.sh "12 1221"
