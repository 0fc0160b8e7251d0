#!/bin/bash
# Check 65's tables (compare.md) from its reports (run.sh, copied here) and checks 64/64d's; from anywhere.
set -euo pipefail
cd "$(dirname "$0")/../../.."  # the repository root
C="python docs/results/2026-11-30-report-1167/compare64d.py"
R=docs/results/2026-11-30-shielded-recipe
O=docs/results/2026-11-30-report-1167
{
  echo "## 1. Each line with its own file (shipped as built, SL shielded)"; echo
  .venv/bin/$C $O/eval-1167 $R/eval-SL-B shipped SL; echo
  echo "## 2. SL when the shield fails (seed 1167 as built) against SL shielded"; echo
  .venv/bin/$C $R/eval-SL-B $R/eval-SL-A SL-shielded SL-unshielded; echo
  echo "## 3. S (check 64d, the variation model alone) against SL, both shielded"; echo
  .venv/bin/$C $O/eval-64d-S $R/eval-SL-B S SL
} > $R/compare.md
