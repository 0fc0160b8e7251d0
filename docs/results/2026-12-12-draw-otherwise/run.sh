#!/usr/bin/env bash
# plan.md: fresh seed 1249 as built, GGX, a duller plastic, and copies moving, sensed and with hot pixels; C and S
# judged on each. Resumable (a finished set or evaluation is kept); at nice 19.
set -euo pipefail
HERE=$(cd "$(dirname "$0")" && pwd)
cd "$HERE/../../.."
S=.venv/bin/station
R=runs/draw-otherwise
mkdir -p "$R" "$HERE/eval"
echo 19 > /proc/self/autogroup 2>/dev/null || true
export OMP_NUM_THREADS=1 PYTHONPATH=.
V=(--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml
   --count 400 --seed 1249 --defects 0.6 --heldout)
GGX='{"plastic": {"type": "pplastic", "finish": "smooth", "distribution": "ggx"}}'
render() {  # render NAME ARGS...: two shards at once, each resumable
    local name=$1; shift
    [ -f "$R/$name.done" ] && return
    for k in 0 1; do "$S" render --out "data/do-$name-1249" "${V[@]}" --shard "$k/2" "$@" > "$R/$name-$k.log" 2>&1 & done
    wait
    touch "$R/$name.done"
}
derive() {  # derive NAME SCRIPT ARGS...: a copy of the as-built set through an earlier study's script
    local name=$1 script=$2; shift 2
    [ -f "$R/$name.done" ] && return
    rm -rf "data/do-$name-1249"
    .venv/bin/python "$script" data/do-built-1249 "data/do-$name-1249" "$@" > "$R/derive-$name.log" 2>&1
    touch "$R/$name.done"
}
judge() {  # judge ARM FILE SET: station eval unless written
    local out="$HERE/eval/$1-$3"
    [ -f "$out/eval.md" ] || "$S" eval --model "$2" --data "data/do-$3-1249" --val-data data/line-pv-val \
        --no-synthetic --no-plots --out "$out" > "$R/eval-$1-$3.log" 2>&1
}
both() { judge C model/weights/default "$1" & local a=$!; judge S runs/make-model-draw/s "$1"; wait $a; }
SR=docs/results/2026-12-02-sensor-response
render built
both built &
derive motion4 $SR/motion_blur.py 4
derive camera $SR/sensor_response.py camera 1249
derive hot30 docs/results/2026-12-02-spectral/hot_pixels.py 30 1249
wait
render ggx --materials "$GGX"
both ggx
both motion4
render rough --config docs/results/2026-11-28-other-means/rough.toml
both rough
both camera
both hot30
echo "done $(date +%T)"
