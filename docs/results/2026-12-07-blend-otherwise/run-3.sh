#!/usr/bin/env bash
# plan-2.md: seed 1240 through vignetting alone (V), judged by S and C; the validation set through the whole lens chain
# (VAL-ALL), S and C adapted on its good parts, each adapted file on plan.md's ALL set. Resumable; run from anywhere.
set -euo pipefail
HERE=$(cd "$(dirname "$0")" && pwd)
cd "$HERE/../../.."
S=.venv/bin/station
R=runs/blend-otherwise
C=$R/cascade/default
export OMP_NUM_THREADS=1 PYTHONPATH=.
O=docs/results
if [ ! -f $R/vignette.done ]; then
    rm -rf data/bo-vignette-1240
    .venv/bin/python $O/2026-11-29-sensor-optics/resensor.py data/bo-built-1240 data/bo-vignette-1240 vignette \
        > $R/derive-vignette.log 2>&1
    touch $R/vignette.done
fi
if [ ! -f $R/pv-val-allff.done ]; then
    rm -rf data/bo-pv-val-allff
    .venv/bin/python $O/2026-11-29-fireflies/reexpose.py data/line-pv-val data/bo-pv-val-allff all \
        > $R/derive-pv-val-allff.log 2>&1
    touch $R/pv-val-allff.done
fi
judge() {  # judge NAME FILE SET VAL: station eval unless written
    local out="$HERE/eval/$1-$3"
    [ -f "$out/eval.md" ] || "$S" eval --model "$2" --data "data/bo-$3-1240" --val-data "$4" \
        --no-synthetic --no-plots --out "$out" > "$R/eval-$1-$3.log" 2>&1
}
judge S model/weights/default vignette data/line-pv-val & a=$!
judge C $C vignette data/line-pv-val
wait $a
adapt() {  # adapt NAME FILE: station adapt on VAL-ALL's good validation parts
    [ -f "$R/$1-adapted.json" ] || "$S" adapt --model "$2" --good data/bo-pv-val-allff --split val \
        --out "$R/$1-adapted" > "$R/adapt-$1.log" 2>&1
}
adapt S model/weights/default & a=$!
adapt C $C
wait $a
judge SA $R/S-adapted allff data/bo-pv-val-allff & a=$!
judge CA $R/C-adapted allff data/bo-pv-val-allff
wait $a
.venv/bin/python "$HERE/read-2.py" > "$HERE/read-2.txt"
echo "done $(date +%T)"
