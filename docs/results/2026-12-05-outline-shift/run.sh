#!/usr/bin/env bash
# plan.md's reading: station bench shift for B (the shipped file with the outline check off) and S (the shipped
# file) on seed 1196's held-out line with line-pv-val's thresholds. Resumable (rendered shards and finished benches
# are kept). Run from anywhere.
set -euo pipefail
HERE=$(cd "$(dirname "$0")" && pwd)
cd "$HERE/../../.."
R=runs/outline-shift
mkdir -p "$R"
export OMP_NUM_THREADS=1
PRESET=(--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml)
render() {  # render OUT ARGS...: two shards in parallel, each resumable (as scripts/make-model.sh renders)
    local out=$1; shift
    for k in 0 1; do .venv/bin/station render --out "$out" "${PRESET[@]}" --shard "$k/2" "$@" & done; wait
}
render data/line-heldout-1196 --count 400 --seed 1196 --defects 0.6 --heldout --visibility > "$R/render-1196.log" 2>&1
render data/line-pv-val --config sim/presets/panel-vary.toml --count 600 --seed 303 --defects 0.4 --validation \
    > "$R/render-val.log" 2>&1
[ -f "$R/B.json" ] || .venv/bin/python -c "import sys; from model.draem.checkpoint import copy_checkpoint; \
copy_checkpoint(*sys.argv[1:])" model/weights/default "$R/B"
.venv/bin/python "$HERE/outline_off.py" "$R/B"
for f in B S; do
    m=$R/B; [ $f = S ] && m=model/weights/default
    [ -f "$R/$f/shift.json" ] || env -u OMP_NUM_THREADS .venv/bin/station bench shift --model "$m" \
        --data data/line-heldout-1196 --val-data data/line-pv-val --out "$R/$f" > "$R/bench-$f.log" 2>&1
    for x in md json; do sed "s|$PWD/||g" "$R/$f/shift.$x" > "$HERE/shift-$f.$x"; done
done
(cd "$HERE" && ../../../.venv/bin/python read.py > read.txt)
