#!/usr/bin/env bash
# plan.md's study: the shipped blend S against its cascade C on fresh seed 1240 rendered as built and under GGX, and
# seven copies of the as-built set moving, sensed and lensed otherwise; station bench shift of both on the as-built
# set. Run from anywhere; resumable (a finished set, evaluation or bench is kept). STEP=render|derive|eval|shift|all.
set -euo pipefail
HERE=$(cd "$(dirname "$0")" && pwd)
cd "$HERE/../../.."
BIN=.venv/bin
S=$BIN/station
R=runs/blend-otherwise
mkdir -p "$R"
export OMP_NUM_THREADS=1 PYTHONPATH=.
STEP=${STEP:-all}
C=$R/cascade/default   # the same file without the blend: the shipped file before stop 123's b0b178d4
if [ ! -f $C.json ]; then
    mkdir -p "$(dirname $C)"
    for x in pt json; do git show b0b178d4^:model/weights/default.$x > $C.$x; done
fi
V=(--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml
   --count 400 --seed 1240 --defects 0.6 --heldout)
GGX='{"plastic": {"type": "pplastic", "finish": "smooth", "distribution": "ggx"}}'
render() {  # render NAME ARGS...: two shards at once, each resumable
    local name=$1; shift
    [ -f "$R/$name.done" ] && return
    for k in 0 1; do "$S" render --out "data/bo-$name-1240" "${V[@]}" --shard "$k/2" "$@" > "$R/$name-$k.log" 2>&1 & done
    wait
    touch "$R/$name.done"
}
if [ "$STEP" = render ] || [ "$STEP" = all ]; then
    render built
    render ggx --materials "$GGX"
fi
derive() {  # derive NAME SCRIPT ARGS...: a copy of the as-built set through an earlier study's script
    local name=$1 script=$2; shift 2
    [ -f "$R/$name.done" ] && return
    rm -rf "data/bo-$name-1240"
    "$BIN/python" "$script" data/bo-built-1240 "data/bo-$name-1240" "$@" > "$R/derive-$name.log" 2>&1
    touch "$R/$name.done"
}
SR=docs/results/2026-12-02-sensor-response
FF=docs/results/2026-11-29-fireflies/reexpose.py
if [ "$STEP" = derive ] || [ "$STEP" = all ]; then
    derive motion2 $SR/motion_blur.py 2 & a=$!
    derive motion4 $SR/motion_blur.py 4; wait $a
    derive pedestal256 $SR/sensor_response.py pedestal256 1240 & a=$!
    derive camera $SR/sensor_response.py camera 1240; wait $a
    derive hot30 docs/results/2026-12-02-spectral/hot_pixels.py 30 1240 & a=$!
    derive blurff $FF blur; wait $a
    derive allff $FF all
fi
judge() {  # judge ARM FILE SET: station eval unless written
    local out="$HERE/eval/$1-$3"
    [ -f "$out/eval.md" ] || "$S" eval --model "$2" --data "data/bo-$3-1240" --val-data data/line-pv-val \
        --no-synthetic --no-plots --out "$out" > "$R/eval-$1-$3.log" 2>&1
}
SETS=(built ggx motion2 motion4 pedestal256 camera hot30 blurff allff)
if [ "$STEP" = eval ] || [ "$STEP" = all ]; then
    for set in "${SETS[@]}"; do
        judge S model/weights/default "$set" & a=$!
        judge C $C "$set"
        wait $a
    done
    "$BIN/python" "$HERE/read.py" > "$HERE/read.txt"
fi
if [ "$STEP" = shift ] || [ "$STEP" = all ]; then  # station bench shift, both files, as built
    for m in S:model/weights/default C:$C; do
        out="$HERE/shift-${m%%:*}"
        [ -f "$out/shift.json" ] || "$S" bench shift --model "${m#*:}" --data data/bo-built-1240 \
            --val-data data/line-pv-val --out "$out" > "$R/shift-${m%%:*}.log" 2>&1 &
    done
    wait
fi
echo "done $(date +%T)"
