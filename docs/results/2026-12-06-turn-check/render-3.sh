#!/usr/bin/env bash
# plan-3.md's fresh sets: T-12 (seed 1230) and T-20 (seed 1231), the camera turned 12 and 20 degrees the other way,
# rendered as render.sh's (they ran at first both at once, four shards; the samples are the same either way).
# Resumable; run from the repository's root.
set -euo pipefail
D=docs/results/2026-12-06-turn-check
exec "$D/render.sh" "-12 1230 $D/turned-12.toml" "-20 1231 $D/turned-20.toml"
