#!/bin/bash
# A second report set for the new kinds (plan.md's measurement again, and two-cameras.sh's): fresh seed 1181, the line
# camera's and the side camera's renders of the same 400 parts, each camera's file evaluated, the pair at rule 64's
# split. Written before anything of seed 1181 was rendered; a report, no decision. Resumable.
set -euo pipefail
cd "$(dirname "$0")/../../.."  # the repository root
D=docs/results/2026-12-01-new-kinds
R=runs/c76
SEED=1181
export OMP_NUM_THREADS=1
P="--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml"
for view in line side; do
  extra=""; [ $view = side ] && extra="--config sim/presets/side-view.toml"
  for k in 0 1; do
    # shellcheck disable=SC2086
    .venv/bin/station render --out data/new-kinds-$view-$SEED $P $extra --config sim/presets/new-kinds.toml \
      --count 400 --seed $SEED --defects 0.6 --heldout --visibility --shard $k/2 > $R/render-$view-$SEED-$k.log 2>&1 &
  done
  wait
done
E="--no-synthetic --no-plots"
[ -f $R/eval-line-$SEED/scores.csv ] || .venv/bin/station eval --model model/weights/default \
  --data data/new-kinds-line-$SEED --val-data data/line-pv-val $E --out $R/eval-line-$SEED > $R/eval-line-$SEED.log 2>&1
[ -f $R/eval-side-$SEED/scores.csv ] || .venv/bin/station eval --model runs/make-side-model/side \
  --data data/new-kinds-side-$SEED --val-data data/sw-pv-val --presence-rule row_contrast $E --out $R/eval-side-$SEED \
  > $R/eval-side-$SEED.log 2>&1
.venv/bin/station compare $R/eval-line-$SEED $R/eval-side-$SEED \
  --split docs/results/2026-11-30-threshold-counts/split-b1.json --out $R/two-cameras-$SEED
mkdir -p $D/seed-$SEED
cp $R/two-cameras-$SEED/* $D/seed-$SEED/
cp $R/eval-line-$SEED/eval.md $D/seed-$SEED/eval-line.md
cp $R/eval-side-$SEED/eval.md $D/seed-$SEED/eval-side.md
