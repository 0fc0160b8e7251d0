#!/usr/bin/env bash
# The second camera's model, from nothing, in one command: `make side-model` (or this script). The second camera is
# a side camera at belt level under a flat dome (sim/presets/side-view.toml, layered last on the line's presets), which
# sees the front faces the line camera sees poorly (docs/results/2026-11-30-side-view.md). The recipe is check 69's
# file WS (docs/results/2026-11-30-side-look.md). Every step resumes: rerun it after an interruption and finished work
# is kept (renders per sample, fits per output file). About 1.5-2 h on 2 cores (renders about an hour; the fit and the
# look network, 25 min, beside one of them: docs/results/2026-11-30-two-camera-station.md).
#
#   1. render the side camera's sets, twins of make-model.sh's (same seeds and parts, seen from the side): training
#      (seed 101, its train split only, the panel, the finish and the edges drawn), calibration (seed 303, the same
#      draws) and validation (seed 303, the panel drawn, the finish and edges as built); and, for step 6, the line
#      camera's validation set (make-model.sh's VAL), the side validation set's twin. Each part's chamfer is drawn
#      0-0.4 mm as make-model.sh draws it (rule 67; the side camera sees the front edges face on:
#      docs/results/2026-12-04-side-edges.md)
#   2. source: the shipped line file's networks and normalisation (SOURCE, default model/weights/default: intensity
#      alone), its variation model and look dropped (model.draem.with_variation.networks_only); the networks do not
#      decide. Since 2026-12-05 (docs/results/2026-12-05-side-intensity.md: as good as built, more robust rendered
#      otherwise, and faster). The side file before read DoLP and AoLP too: its source was git 0f17840^'s
#      model/weights/default (git show it to a file and pass that as SOURCE to make it again)
#   3. variation: fitted on the side training set's good parts, calibrated on the calibration set (station variation
#      --refit)
#   4. look: one residual network beside it at each one's 1 % threshold (station residual --second-look); 3-4 run on
#      one core while the side validation set renders on the other
#   5. threshold: on the side validation set, leaving out frames its presence rule (row_contrast) calls empty
#   6. split: the two cameras' thresholds from one 1 % budget on the two validation sets (station split; the budget
#      that holds 1 % for new good parts on average, rule 64), printed as the station.toml lines of [decision]
#      threshold and [second_camera] threshold
set -euo pipefail
cd "$(dirname "$0")/.."
BIN=${BIN:-.venv/bin}
RUNS=${RUNS:-runs/make-side-model}
OUT=${OUT:-$RUNS/side}
SIDE_TRAIN=${SIDE_TRAIN:-data/sw-train}
SIDE_CAL=${SIDE_CAL:-data/sw-pf-val}
SIDE_VAL=${SIDE_VAL:-data/sw-pv-val}
LINE_VAL=${LINE_VAL:-data/line-pv-val}
LINE_MODEL=${LINE_MODEL:-model/weights/default}
SOURCE=${SOURCE:-model/weights/default}  # a checkpoint, path without suffix
LOOK_STEPS=${LOOK_STEPS:-3000}
TRAIN_COUNT=${TRAIN_COUNT:-900}
VAL_COUNT=${VAL_COUNT:-600}
PRESET=(--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml)
VARY=(--config sim/presets/panel-vary.toml)
FINISH=(--config sim/presets/finish-vary.toml)
EDGES=(--edge-mm 0,0.4)  # training and calibration only, as make-model.sh's (rule 67)
SIDE=(--config sim/presets/side-view.toml)  # last: the second camera and its flat dome
export OMP_NUM_THREADS=${OMP_NUM_THREADS:-1}  # one thread per process: see docs/platform-facts.md
mkdir -p "$RUNS"

render() {  # render OUT ARGS...: two shards in parallel, each resumable
    local out=$1; shift
    "$BIN/station" render --out "$out" "${PRESET[@]}" --shard 0/2 "$@" & local a=$!
    "$BIN/station" render --out "$out" "${PRESET[@]}" --shard 1/2 "$@" & local b=$!
    wait "$a"; wait "$b"
}

# 1. the train split only (sample k % 10 >= 3): the shards k of 20 with k % 10 >= 3, half in each process
for half in 0 1; do
    (for j in 3 4 5 6 7 8 9; do
        "$BIN/station" render --out "$SIDE_TRAIN" "${PRESET[@]}" "${VARY[@]}" "${FINISH[@]}" "${EDGES[@]}" \
            "${SIDE[@]}" --count "$TRAIN_COUNT" --seed 101 --defects 0.4 --defects-in-train \
            --shard $((j + 10 * half))/20
    done) & pids[half]=$!
done
wait "${pids[0]}"; wait "${pids[1]}"
render "$SIDE_CAL" "${VARY[@]}" "${FINISH[@]}" "${EDGES[@]}" "${SIDE[@]}" --count "$VAL_COUNT" --seed 303 \
    --defects 0.4 --validation

# 2. the source: the line file's networks and normalisation
if [ ! -f "$RUNS/source/default.json" ]; then
    "$BIN/python" -c "import sys; from model.draem.checkpoint import load_checkpoint, save_checkpoint; \
from model.draem.with_variation import networks_only; \
save_checkpoint(sys.argv[2], networks_only(load_checkpoint(sys.argv[1]).detector))" "$SOURCE" "$RUNS/source/default"
fi

# 3-4. the variation model and its look network (one core), beside the side validation set's render (the other)
fit() {
    [ -f "$RUNS/fit.json" ] || "$BIN/station" variation --model "$RUNS/source/default" --refit --data "$SIDE_TRAIN" \
        --val-data "$SIDE_CAL" --decision variation --out "$RUNS/fit"
    [ -f "$OUT.json" ] || [ -f "$RUNS/look.json" ] || "$BIN/station" residual --model "$RUNS/fit" \
        --data "$SIDE_TRAIN" --val-data "$SIDE_CAL" --members 1 --steps "$LOOK_STEPS" --second-look --out "$RUNS/look"
}
fit & fitting=$!
"$BIN/station" render --out "$SIDE_VAL" "${PRESET[@]}" "${VARY[@]}" "${SIDE[@]}" --count "$VAL_COUNT" --seed 303 \
    --defects 0.4 --validation
wait "$fitting"

# 5. the threshold
if [ ! -f "$OUT.json" ]; then
    "$BIN/station" threshold --model "$RUNS/look" --data "$SIDE_VAL" --presence-rule row_contrast
    "$BIN/python" -c "import sys; from model.draem.checkpoint import copy_checkpoint; copy_checkpoint(*sys.argv[1:])" \
        "$RUNS/look" "$OUT"
fi

# 6. the split of the two thresholds, on the line camera's twin of the side validation set
render "$LINE_VAL" "${VARY[@]}" --count "$VAL_COUNT" --seed 303 --defects 0.4 --validation
"$BIN/station" split --model "$LINE_MODEL" --data "$LINE_VAL" --second-model "$OUT" --second-data "$SIDE_VAL" \
    --out "$RUNS/split.json"
echo "the side camera's model: $OUT (station.toml: [second_camera] model = \"$OUT\", and the two thresholds above)"
