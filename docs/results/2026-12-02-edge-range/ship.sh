#!/bin/bash
# After rule 67 ships E63 (model/weights/default is then E63; the file before is kept as runs/c86/F63): the new
# file's report set, seed 1187 (the line as built, 400 parts, rendered after the decision), its evaluation into
# model/weights/default-eval, a pipeline bench of both files in one run, and the held-out types (the look network
# trained again without each type, thresholded as the shipped file: make model's step 7). Two lanes; resumable.
set -euo pipefail
cd "$(dirname "$0")/../../.."  # the repository root
S=docs/results/2026-12-02-edge-range
R=runs/c86
export PYTHONPATH=. OMP_NUM_THREADS=1
V="--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml"
render() {  # shard k of 2 of seed 1187
  [ -f $R/report-1187-$1.done ] && return
  .venv/bin/station render $V --count 400 --seed 1187 --defects 0.6 --heldout --visibility --shard $1/2 \
    --out data/line-panel-heldout-1187 > $R/report-1187-$1.log 2>&1
  touch $R/report-1187-$1.done
}
holdout() {  # the look network without type $1, thresholded on the line as built
  [ -f $R/holdout-$1.done ] && return
  .venv/bin/station residual --model $R/Ev --data data/line-ef-train --val-data data/line-ef-val --members 1 \
    --steps 3000 --second-look --holdout-type $1 --out $R/holdout-$1 > $R/holdout-$1.log 2>&1
  .venv/bin/station threshold --model $R/holdout-$1 --data data/line-pv-val > $R/holdout-$1-threshold.log 2>&1
  touch $R/holdout-$1.done
}
ev() { [ -f $2/eval.md ] || .venv/bin/station eval --model $1 --data data/line-panel-heldout-1187 \
  --val-data data/line-pv-val "${@:3}" --out $2 > $R/$(basename $2).log 2>&1; }
(render 0
 while [ ! -f $R/report-1187-1.done ]; do sleep 10; done
 ev model/weights/default model/weights/default-eval
 rm -f model/weights/default-eval/eval.json
 [ -f $S/bench/pipeline.md ] || .venv/bin/station bench pipeline --data data/line-panel-heldout-1186 \
   --models model/weights/default,$R/F63 --methods bilinear --precisions fp32 --parts 150 --out $S/bench \
   > $R/bench.log 2>&1
 holdout dent
 holdout scratch) &
a=$!
render 1
holdout stain
holdout chip
holdout missing_stud
wait $a
for t in dent scratch stain chip missing_stud; do
  ev $R/holdout-$t $S/heldout/eval-holdout-$t --no-synthetic --no-plots
done
echo "ship done $(date +%T)"
