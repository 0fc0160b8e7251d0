#!/usr/bin/env bash
# plan.md's study: candidate L (runs/make-model-lens/band-look, made by `LENS=sim/presets/lens-vary.toml make model`
# with SHIP=0) against the shipped file S on fresh sets B (seed 1241, as built), V (B through plan 2's lens chain)
# and N (seed 1242, kinds nobody rendered). Everything here runs at nice 19 beside make model. Run from anywhere;
# resumable (a finished set or evaluation is kept). L's evaluations wait until make model has evaluated L.
set -euo pipefail
HERE=$(cd "$(dirname "$0")" && pwd)
cd "$HERE/../../.."
BIN=.venv/bin
S=$BIN/station
R=runs/lens-train
mkdir -p "$R" "$HERE/eval"
echo 19 > /proc/self/autogroup 2>/dev/null || true  # nice across sessions: Linux autogroups ignore a process's own nice
export OMP_NUM_THREADS=1 PYTHONPATH=.
L=runs/make-model-lens/band-look
PRESET=(--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml
        --count 400 --defects 0.6 --heldout)
render() {  # render DIR ARGS...: two shards at once, each resumable
    local dir=$1; shift
    [ -f "$R/$(basename "$dir").done" ] && return
    for k in 0 1; do nice -n 19 "$S" render --out "$dir" "${PRESET[@]}" --shard "$k/2" "$@" \
        > "$R/$(basename "$dir")-$k.log" 2>&1 & done
    wait
    touch "$R/$(basename "$dir").done"
}
render data/lt-built-1241 --seed 1241
if [ ! -f "$R/allff.done" ]; then  # V: B through the whole lens chain (blur, vignetting, three imperfections)
    rm -rf data/lt-allff-1241
    nice -n 19 "$BIN/python" docs/results/2026-11-29-fireflies/reexpose.py data/lt-built-1241 data/lt-allff-1241 all \
        > "$R/derive-allff.log" 2>&1
    touch "$R/allff.done"
fi
render data/lt-new-1242 --config sim/presets/new-kinds.toml --seed 1242
judge() {  # judge ARM MODEL VAL SET: station eval unless written (each file's threshold from its own validation set)
    local out="$HERE/eval/$1-$4"
    [ -f "$out/eval.md" ] || nice -n 19 "$S" eval --model "$2" --data "data/lt-$4" --val-data "$3" \
        --no-synthetic --no-plots --out "$out" > "$R/eval-$1-$4.log" 2>&1
}
SETS=(built-1241 allff-1241 new-1242)
judge S model/weights/default data/line-pv-val "${SETS[0]}" & a=$!
judge S model/weights/default data/line-pv-val "${SETS[1]}"; wait $a
judge S model/weights/default data/line-pv-val "${SETS[2]}"
until [ -f runs/make-model-lens/eval-band-look/eval.md ]; do sleep 60; done
judge L $L data/lens-pv-val "${SETS[0]}" & a=$!
judge L $L data/lens-pv-val "${SETS[1]}"; wait $a
judge L $L data/lens-pv-val "${SETS[2]}"
echo "done $(date +%T)"
