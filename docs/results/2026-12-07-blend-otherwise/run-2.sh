#!/usr/bin/env bash
# plan.md's addendum: seed 1240 under a duller plastic and under the panel at half its radiance, each judged by S and
# C as run.sh's sets are, then read.py again. Resumable; run from anywhere after run.sh.
set -euo pipefail
HERE=$(cd "$(dirname "$0")" && pwd)
cd "$HERE/../../.."
S=.venv/bin/station
R=runs/blend-otherwise
C=$R/cascade/default
export OMP_NUM_THREADS=1 PYTHONPATH=.
V=(--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml
   --count 400 --seed 1240 --defects 0.6 --heldout)
O=docs/results
render() {  # render NAME ARGS...: two shards at once, each resumable
    local name=$1; shift
    [ -f "$R/$name.done" ] && return
    for k in 0 1; do "$S" render --out "data/bo-$name-1240" "${V[@]}" --shard "$k/2" "$@" > "$R/$name-$k.log" 2>&1 & done
    wait
    touch "$R/$name.done"
}
render rough --config $O/2026-11-28-other-means/rough.toml
render half --config $O/2026-11-29-panel-brightness/half.toml
judge() {  # judge ARM FILE SET: station eval unless written
    local out="$HERE/eval/$1-$3"
    [ -f "$out/eval.md" ] || "$S" eval --model "$2" --data "data/bo-$3-1240" --val-data data/line-pv-val \
        --no-synthetic --no-plots --out "$out" > "$R/eval-$1-$3.log" 2>&1
}
for set in rough half; do
    judge S model/weights/default "$set" & a=$!
    judge C $C "$set"
    wait $a
done
.venv/bin/python "$HERE/read.py" > "$HERE/read.txt"
echo "done $(date +%T)"
