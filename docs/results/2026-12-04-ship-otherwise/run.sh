#!/usr/bin/env bash
# The study (plan.md): the shipped intensity-only file S against E63 on fresh seed 1196 rendered as built, with edges
# chamfered or rounded 0.3 mm, and five copies of the as-built set carrying a moving part or a sensor's response.
# Run from anywhere; resumable (a finished sample, set or evaluation is kept). STEP=render|derive|eval|all (default).
set -euo pipefail
HERE=$(cd "$(dirname "$0")" && pwd)
cd "$HERE/../../.."
BIN=.venv/bin
S=$BIN/station
R=runs/ship-otherwise
mkdir -p "$R"
export OMP_NUM_THREADS=1 PYTHONPATH=.
STEP=${STEP:-all}
E63=runs/make-model-r/e63   # the file before (shipped 2026-12-02 to 2026-12-04): git show 9cf5dec:model/weights/default.*
if [ ! -f $E63.json ]; then
    mkdir -p "$(dirname $E63)"
    for x in pt json; do git show 9cf5dec:model/weights/default.$x > $E63.$x; done
fi
V=(--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml
   --count 400 --seed 1196 --defects 0.6 --heldout)
render() {  # render NAME ARGS...: two shards at once, each resumable
    local name=$1; shift
    [ -f "$R/$name.done" ] && return
    for k in 0 1; do "$S" render --out "data/$name" "${V[@]}" --shard "$k/2" "$@" > "$R/$name-$k.log" 2>&1 & done
    wait
    touch "$R/$name.done"
}
if [ "$STEP" = render ] || [ "$STEP" = all ]; then
    render so-built-1196
    render so-chamfer03-1196 --edge-mm 0.3
    render so-round03-1196 --edge-mm 0.3 --edge-shape round --config docs/results/2026-12-02-edge-range/no-chips.toml
fi
derive() {  # derive NAME SCRIPT ARGS...: a copy of the as-built set through an earlier study's script
    local name=$1 script=$2; shift 2
    [ -f "$R/$name.done" ] && return
    rm -rf "data/$name"
    "$BIN/python" "$script" data/so-built-1196 "data/$name" "$@"
    touch "$R/$name.done"
}
SR=docs/results/2026-12-02-sensor-response
if [ "$STEP" = derive ] || [ "$STEP" = all ]; then
    derive so-motion2-1196 $SR/motion_blur.py 2
    derive so-motion4-1196 $SR/motion_blur.py 4
    derive so-pedestal256-1196 $SR/sensor_response.py pedestal256 1196
    derive so-camera-1196 $SR/sensor_response.py camera 1196
    derive so-hot30-1196 docs/results/2026-12-02-spectral/hot_pixels.py 30 1196
fi
judge() {  # judge FILE-NAME FILE SET: station eval unless written
    local out="$HERE/eval/$1-$3"
    [ -f "$out/eval.md" ] || "$S" eval --model "$2" --data "data/so-$3-1196" --val-data data/line-pv-val \
        --no-synthetic --no-plots --out "$out" > "$R/eval-$1-$3.log" 2>&1
}
if [ "$STEP" = remedy ] || [ "$STEP" = all ]; then  # after the reads: the pedestal set, its black level stated
    if [ ! -f "$R/so-pedestal256bl-1196.done" ]; then
        rm -rf data/so-pedestal256bl-1196 && mkdir -p data/so-pedestal256bl-1196
        ln -s "$PWD/data/so-pedestal256-1196/samples" data/so-pedestal256bl-1196/samples
        "$BIN/python" -c "import json, sys; m = json.load(open(sys.argv[1])); m['black_level'] = 256; \
json.dump(m, open(sys.argv[2], 'w'), indent=1)" data/so-pedestal256-1196/manifest.json \
            data/so-pedestal256bl-1196/manifest.json
        touch "$R/so-pedestal256bl-1196.done"
    fi
    judge S model/weights/default pedestal256bl
fi
if [ "$STEP" = lens ] || [ "$STEP" = all ]; then  # the addendum: re-exposed through the lens as plan 68 did
    for kind in blur all; do
        if [ ! -f "$R/so-${kind}ff-1196.done" ]; then
            rm -rf "data/so-${kind}ff-1196"
            "$BIN/python" docs/results/2026-11-29-fireflies/reexpose.py data/so-built-1196 "data/so-${kind}ff-1196" \
                $kind > "$R/reexpose-$kind.log" 2>&1
            touch "$R/so-${kind}ff-1196.done"
        fi
        judge S model/weights/default ${kind}ff & a=$!
        judge E63 $E63 ${kind}ff
        wait $a
    done
fi
if [ "$STEP" = eval ] || [ "$STEP" = all ]; then
    for set in built chamfer03 round03 motion2 motion4 pedestal256 camera hot30; do
        judge S model/weights/default $set & a=$!
        judge E63 $E63 $set
        wait $a
    done
    "$BIN/python" "$HERE/read.py" > "$HERE/read.txt"
    "$BIN/python" "$HERE/plot.py"
fi
if [ "$STEP" = shift ] || [ "$STEP" = all ]; then  # after the reads: station bench shift, both files, as built
    for m in S:model/weights/default E63:$E63; do
        out="$HERE/shift-${m%%:*}"
        [ -f "$out/shift.json" ] || env -u OMP_NUM_THREADS "$S" bench shift --model "${m#*:}" \
            --data data/so-built-1196 --val-data data/line-pv-val --out "$out" > "$R/shift-${m%%:*}.log" 2>&1 &
    done
    wait
fi
echo "done $(date +%T)"
