#!/bin/bash
# Plan 69 end to end (plan.md, as amended at stop 89), from anywhere; resumable: every step skips what is done.
# Waits for a render.sh train already running, then the calibration set, the fit (run.sh) and the rule (rule.sh).
set -euo pipefail
S="$(dirname "$0")"
while pgrep -f "lobe-fit/render.sh train" > /dev/null; do sleep 20; done
"$S"/render.sh train
"$S"/render.sh cal
"$S"/run.sh
"$S"/rule.sh
