#!/usr/bin/env bash
# plan.md's fresh sets (rendered before candidate Q exists; read only once it does): B' (seed 1243, as built),
# V' (B' through the whole lens chain), N' (seed 1244, kinds nobody rendered); S evaluated on each; then, once
# make-q.sh has made Q, Q and read.py Q; then, once it has made the control R, R and read.py R. Resumable; at nice 19
# (autogroup).
set -euo pipefail
HERE=$(cd "$(dirname "$0")" && pwd)
cd "$HERE/../../.."
BIN=.venv/bin
R=runs/smooth-field
mkdir -p "$R"
echo 19 > /proc/self/autogroup 2>/dev/null || true  # nice across sessions: Linux autogroups ignore a process's own nice
export OMP_NUM_THREADS=1 PYTHONPATH=.
PRESET=(--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml
        --count 400 --defects 0.6 --heldout)
render() {  # render DIR ARGS...: two shards at once, each resumable
    local dir=$1; shift
    [ -f "$R/$(basename "$dir").done" ] && return
    for k in 0 1; do "$BIN/station" render --out "$dir" "${PRESET[@]}" --shard "$k/2" "$@" \
        > "$R/$(basename "$dir")-$k.log" 2>&1 & done
    wait
    touch "$R/$(basename "$dir").done"
}
render data/sf-built-1243 --seed 1243
if [ ! -f "$R/allff.done" ]; then
    rm -rf data/sf-allff-1243
    "$BIN/python" docs/results/2026-11-29-fireflies/reexpose.py data/sf-built-1243 data/sf-allff-1243 all \
        > "$R/derive-allff.log" 2>&1
    touch "$R/allff.done"
fi
render data/sf-new-1244 --config sim/presets/new-kinds.toml --seed 1244
echo "sets done $(date +%T)"
mkdir -p "$HERE/eval"
judge() {  # judge ARM MODEL SET: station eval unless written (thresholds stored; 1 and 5 % from data/line-pv-val)
    local out="$HERE/eval/$1-$3"
    [ -f "$out/eval.md" ] || "$BIN/station" eval --model "$2" --data "data/sf-$3" --val-data data/line-pv-val \
        --no-synthetic --no-plots --out "$out" > "$R/eval-$1-$3.log" 2>&1
}
each() {  # each ARM MODEL: judge the model on the three sets, two at once
    judge "$1" "$2" built-1243 & local a=$!
    judge "$1" "$2" allff-1243; wait $a
    judge "$1" "$2" new-1244
}
until grep -qs "render	data/line-pv-val" runs/make-model-sf/timings.tsv; do sleep 60; done  # make-q.sh rendered VAL
each S model/weights/default
until [ -f runs/make-model-sf/eval-band-look/eval.md ]; do sleep 60; done  # Q made (make-q.sh; make model evaluated it)
each Q runs/make-model-sf/band-look
"$BIN/python" "$HERE/read.py" Q
echo "Q read $(date +%T)"
until [ -f runs/make-model-r/eval-band-look/eval.md ]; do sleep 60; done  # the control R made (make-q.sh)
each R runs/make-model-r/band-look
"$BIN/python" "$HERE/read.py" R
echo "done $(date +%T)"
