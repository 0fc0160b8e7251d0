#!/bin/bash
# The fireflies page's table, from the repository root (the reports beside this script; rule 56's and rule 60's
# reports of the sets with the fireflies spread, where they were first written).
D=docs/results/2026-11-29-fireflies
PYTHONPATH=. .venv/bin/python $D/table.py \
  "K3, 1157 as built=$D/eval-K3-asbuilt-1157" \
  "K3, 1157 blur, fireflies spread=$D/eval-K3-blur-1157" \
  "K3, 1157 blur=$D/eval-K3-blurff-1157" \
  "C, 1157 as built=$D/eval-C-asbuilt-1157" \
  "C, 1157 blur, fireflies spread=$D/eval-C-blur-1157" \
  "C, 1157 blur=$D/eval-C-blurff-1157" \
  "K3, 1159 as built=$D/eval-K3-asbuilt-1159" \
  "K3, 1159 all five, fireflies spread=docs/results/2026-11-29-curvature/eval-K3-all" \
  "K3, 1159 all five=$D/eval-K3-allff-1159" \
  "C, 1159 as built=docs/results/2026-11-29-operating-point/eval-X-1159" \
  "C, 1159 all five, fireflies spread=docs/results/2026-11-29-operating-point/eval-X-all" \
  "C, 1159 all five=$D/eval-C-allff-1159"
