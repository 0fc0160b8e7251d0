#!/usr/bin/env bash
# plan.md: the lens validation set, the fresh sets B2, V2, N2, the choice among S, R, R1, R2 (runs/look-lens, made by
# ../2026-12-10-look-lens/make-a.sh and spread.sh), and each read. Resumable (renders per sample; each output once
# written is kept); at nice 19.
set -euo pipefail
HERE=$(cd "$(dirname "$0")" && pwd)
cd "$HERE/../../.."
BIN=.venv/bin
R=runs/look-draw L=runs/look-lens
mkdir -p "$R" "$HERE/eval"
echo 19 > /proc/self/autogroup 2>/dev/null || true  # nice across sessions: Linux autogroups ignore a process's own nice
export OMP_NUM_THREADS=1 PYTHONPATH=.
PRESET=(--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml)
HELD=(--count 400 --defects 0.6 --heldout)
render() {  # render DIR ARGS...: two shards at once, each resumable (make-model.sh's commands)
    local dir=$1; shift
    [ -f "$R/$(basename "$dir").done" ] && return
    for k in 0 1; do "$BIN/station" render --out "$dir" "${PRESET[@]}" --shard "$k/2" "$@" \
        > "$R/$(basename "$dir")-$k.log" 2>&1 & done
    wait
    touch "$R/$(basename "$dir").done"
}
render data/line-pv-val-lens --config sim/presets/panel-vary.toml --config sim/presets/lens-vary.toml --count 600 \
    --seed 303 --defects 0.4 --validation
render data/line-heldout-1247 "${HELD[@]}" --seed 1247
render data/ll-new-1248 "${HELD[@]}" --config sim/presets/new-kinds.toml --seed 1248
if [ ! -f "$R/allff.done" ]; then
    rm -rf data/ll-allff-1247
    "$BIN/python" docs/results/2026-11-29-fireflies/reexpose.py data/line-heldout-1247 data/ll-allff-1247 all \
        > "$R/derive-allff.log" 2>&1
    touch "$R/allff.done"
fi
echo "sets done $(date +%T)"
[ -f "$R/C.json" ] || "$BIN/station" pick --models model/weights/default "$L/R" "$L/R1" "$L/R2" \
    --data data/line-pv-val-lens --out "$R/C" | tee "$R/pick.txt"
cp "$R/pick.txt" "$HERE/pick.txt"
judge() {  # judge ARM MODEL SET: station eval unless written (thresholds stored; 1 and 5 % from data/line-pv-val)
    local out="$HERE/eval/$1-$3" data=data/ll-$3
    [ "$3" = built-1247 ] && data=data/line-heldout-1247
    [ -f "$out/eval.md" ] || "$BIN/station" eval --model "$2" --data "$data" --val-data data/line-pv-val \
        --no-synthetic --no-plots --out "$out" > "$R/eval-$1-$3.log" 2>&1
}
if grep -q "kept: model/weights/default" "$R/pick.txt"; then echo "the choice keeps S: nothing to read"; exit 0; fi
for set in built-1247 allff-1247 new-1248; do
    judge S model/weights/default "$set" & s=$!
    judge C "$R/C" "$set"; wait $s
done
"$BIN/python" "$HERE/read.py"
echo "done $(date +%T)"
