#!/usr/bin/env bash
# plan.md: candidate A (S's look network trained again with lens copies) and the control R (without), from S's own
# variation model, on make model's training, calibration and validation sets; then the fresh sets B, V, N and every
# evaluation, and read.py. Resumable (renders per sample; each file once written is kept); at nice 19.
set -euo pipefail
HERE=$(cd "$(dirname "$0")" && pwd)
cd "$HERE/../../.."
BIN=.venv/bin
R=runs/look-lens
mkdir -p "$R" "$HERE/eval"
echo 19 > /proc/self/autogroup 2>/dev/null || true  # nice across sessions: Linux autogroups ignore a process's own nice
export OMP_NUM_THREADS=1 PYTHONPATH=.
PRESET=(--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml)
VARY=(--config sim/presets/panel-vary.toml) FINISH=(--config sim/presets/finish-vary.toml) EDGES=(--edge-mm 0,0.4)
HELD=(--count 400 --defects 0.6 --heldout)
render() {  # render DIR ARGS...: two shards at once, each resumable (make-model.sh's sets and commands)
    local dir=$1; shift
    [ -f "$R/$(basename "$dir").done" ] && return
    for k in 0 1; do "$BIN/station" render --out "$dir" "${PRESET[@]}" --shard "$k/2" "$@" \
        > "$R/$(basename "$dir")-$k.log" 2>&1 & done
    wait
    touch "$R/$(basename "$dir").done"
}
render data/line-ef-train "${VARY[@]}" "${FINISH[@]}" "${EDGES[@]}" --count 900 --seed 101 --defects 0.4 \
    --defects-in-train
render data/line-ef-val "${VARY[@]}" "${FINISH[@]}" "${EDGES[@]}" --count 600 --seed 303 --defects 0.4 --validation
render data/line-pv-val "${VARY[@]}" --count 600 --seed 303 --defects 0.4 --validation
render data/line-heldout-1245 "${HELD[@]}" --seed 1245
render data/ll-new-1246 "${HELD[@]}" --config sim/presets/new-kinds.toml --seed 1246
if [ ! -f "$R/allff.done" ]; then
    rm -rf data/ll-allff-1245
    "$BIN/python" docs/results/2026-11-29-fireflies/reexpose.py data/line-heldout-1245 data/ll-allff-1245 all \
        > "$R/derive-allff.log" 2>&1
    touch "$R/allff.done"
fi
echo "sets done $(date +%T)"
# S's variation model without its look: what make model's band-variation is, with S's checks
[ -f "$R/s-variation.json" ] || "$BIN/python" -c "
import sys
from model.draem.checkpoint import load_checkpoint, save_checkpoint
from model.draem.detector import Detector
ck = load_checkpoint(sys.argv[1])
d = ck.detector
out = Detector(d.config.with_(residual_members=0), d.normalizer)
out.load_state_dict({k: v for k, v in d.state_dict().items() if not k.startswith('residual.')})
train = {k: v for k, v in ck.meta['train'].items() if k not in ('residual', 'blend', 'threshold_set')}
save_checkpoint(sys.argv[2], out.eval(), threshold=ck.threshold, threshold_rule='S without its look (look-lens)',
                data_manifest_sha256=ck.meta.get('data_manifest_sha256'), train=train)
" model/weights/default "$R/s-variation"
arm() {  # arm NAME ARGS...: the look trained (one thread), blended and thresholded as make model's
    [ -f "$R/$1.done" ] && return
    [ -f "$R/$1.json" ] || "$BIN/station" residual --model "$R/s-variation" --data data/line-ef-train \
        --val-data data/line-ef-val --members 1 --steps 3000 --second-look --out "$R/$1" "${@:2}" > "$R/$1.log" 2>&1
    "$BIN/station" blend --model "$R/$1" --data data/line-pv-val --weight 0.25 --out "$R/$1" >> "$R/$1.log" 2>&1
    "$BIN/station" threshold --model "$R/$1" --data data/line-pv-val >> "$R/$1.log" 2>&1
    touch "$R/$1.done"
}
arm A --lens-copies 0,0.3 & a=$!
arm R; wait $a
judge() {  # judge ARM MODEL SET: station eval unless written (thresholds stored; 1 and 5 % from data/line-pv-val)
    local out="$HERE/eval/$1-$3" data=data/ll-$3
    [ "$3" = built-1245 ] && data=data/line-heldout-1245
    [ -f "$out/eval.md" ] || "$BIN/station" eval --model "$2" --data "$data" --val-data data/line-pv-val \
        --no-synthetic --no-plots --out "$out" > "$R/eval-$1-$3.log" 2>&1
}
for set in built-1245 allff-1245 new-1246; do
    judge S model/weights/default "$set" & s=$!
    judge A "$R/A" "$set"; wait $s
done
"$BIN/python" "$HERE/read.py" A
echo "A read $(date +%T)"
for set in built-1245 allff-1245 new-1246; do judge R "$R/R" "$set"; done
"$BIN/python" "$HERE/read.py" R
echo "done $(date +%T)"
