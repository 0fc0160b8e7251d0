#!/usr/bin/env bash
# The whole ablation in two lanes, one core each (resumable): lane a the R model, then the evaluations; lane b the
# renders, then the RA model. Then the paired comparisons and measure 1 (matched.py).
set -euo pipefail
cd "$(dirname "$0")"
HERE=$PWD
S=../../../.venv/bin/station
RUNS=../../../runs/abl
export OMP_NUM_THREADS=1
evaluate() {  # evaluate NAME MODEL: both seeds, thresholds from the line's validation set
    for seed in 1191 1192; do
        [ -e "eval-$1-$seed/scores.csv" ] || $S eval --model "$2" --data "../../../data/line-heldout-$seed" \
            --val-data ../../../data/line-pv-val --out "eval-$1-$seed"
    done
}
(./models.sh R intensity; evaluate RAD "$RUNS/../make-model-96/band-look"; evaluate R "$RUNS/R-look") \
    > "$RUNS/lane-a.log" 2>&1 & a=$!
(./render.sh; ./models.sh RA intensity,aolp; evaluate RA "$RUNS/RA-look") > "$RUNS/lane-b.log" 2>&1 & b=$!
wait "$a"; wait "$b"
for seed in 1191 1192; do
    $S compare --paired "eval-R-$seed" "eval-RA-$seed" "eval-RAD-$seed" --out "paired-$seed"
    $S compare --paired "eval-RA-$seed" "eval-RAD-$seed" --out "paired-RA-$seed"
done
(cd ../../.. && PYTHONPATH=. .venv/bin/python "$HERE/matched.py") > matched.txt
