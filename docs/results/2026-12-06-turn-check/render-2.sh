#!/usr/bin/env bash
# plan-2.md's fresh set: T-20 (seed 1229, the camera turned 20 degrees the other way), rendered as render.sh's.
# Resumable; run from the repository's root.
set -euo pipefail
D=docs/results/2026-12-06-turn-check
exec "$D/render.sh" "-20 1229 $D/turned-20.toml"
