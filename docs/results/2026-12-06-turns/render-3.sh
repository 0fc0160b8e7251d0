#!/usr/bin/env bash
# plan-3.md's sets T20 (seed 1225) and T30 (seed 1226), rendered as plan 1's sets are (render.sh). Resumable, two
# shards each; run from the repository's root.
set -euo pipefail
exec docs/results/2026-12-06-turns/render.sh "20 1225" "30 1226"
