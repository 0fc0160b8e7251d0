#!/bin/bash
# Check 69's reading (plan.md), after run.sh: check 68's combine68.py, unchanged (its "W" labels name the side
# camera's file, WS here: relabelled), and the side camera's presence rule on the held-out frames.
set -euo pipefail
cd "$(dirname "$0")/../../.."  # the repository root
R=runs/c69
D=docs/results/2026-11-30-side-look
.venv/bin/python docs/results/2026-11-30-wide-dome/combine68.py runs/c67/val-default $R/val-WS $R/eval-line-1171 \
  $R/eval-WS-1171 data/line-panel-heldout-1171 1171 | sed 's/side camera alone (W)/side camera alone (WS)/; s/, W \([0-9]\)/, WS \1/' \
  > $D/combine69-1171.md
.venv/bin/python $D/presence_probe.py data/sw-heldout-1171 > $R/presence-1171.json
.venv/bin/python $D/presence_probe.py --table $R/presence-1171.json > $D/presence-1171.md
