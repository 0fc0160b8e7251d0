#!/usr/bin/env bash
# The shipped file's deciding part fitted again as make model fits it (steps 6 and 6b), timed, on the training set
# make model renders (seed 101, 900 parts) but only its train and val splits (index % 10 in 2..9: the splits the fit
# reads; its test split is never read by the recipe), calibrated on that set's val split (90 parts) instead of
# make model's 600-part calibration set: the per-place statistics the fit stores do not read the calibration set.
# Each command's wall seconds go to runs/recipe-time/timings.tsv. Resumable. Run from the repository root.
set -euo pipefail
BIN=.venv/bin
R=runs/recipe-time
DATA=data/line-ef-train
mkdir -p "$R"
export OMP_NUM_THREADS=1
PRESET=(--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml)
RECIPE=(--config sim/presets/panel-vary.toml --config sim/presets/finish-vary.toml --edge-mm 0,0.4)
timed() {  # timed NAME CMD...: run CMD, then append NAME, its wall seconds and the time to the timings
    local name=$1 t0=$SECONDS; shift
    "$@"
    printf '%s\t%s\t%s\n' "$name" "$((SECONDS - t0))" "$(date -Is)" >> "$R/timings.tsv"
}
shards() {  # the splits index % 10 in 2..9, four shards of 10 per process, two processes
    for half in 0 1; do
        (for j in $((2 + half)) $((4 + half)) $((6 + half)) $((8 + half)); do
            "$BIN/station" render --out "$DATA" "${PRESET[@]}" "${RECIPE[@]}" --count 900 --seed 101 --defects 0.4 \
                --defects-in-train --shard "$j/10"
        done) & pids[half]=$!
    done
    wait "${pids[0]}"; wait "${pids[1]}"
}
timed render shards
# the shipped file without its look network (a refit replaces the fit the look reads, so it refuses a file with one);
# make model fits from its band network, which has none
[ -f "$R/no-look.json" ] || "$BIN/python" - "$R/no-look" <<'PY'
import sys
from model.draem.checkpoint import load_checkpoint, save_checkpoint
from model.draem.detector import Detector
ck = load_checkpoint("model/weights/default")
d = ck.detector
out = Detector(d.config.with_(residual_members=0), d.normalizer)
out.load_state_dict({k: v for k, v in d.state_dict().items() if not k.startswith("residual.")})
save_checkpoint(sys.argv[1], out, threshold=ck.threshold)
PY
[ -f "$R/variation.json" ] || timed variation "$BIN/station" variation --model "$R/no-look" --refit \
    --data "$DATA" --decision variation --out "$R/variation"
[ -f "$R/look.json" ] || timed look "$BIN/station" residual --model "$R/variation" --data "$DATA" --members 1 \
    --steps 3000 --second-look --out "$R/look"
# two held-out looks at once, one per core, as make model's step 7 now runs them: the pair's wall time against one look
pair() {
    local t pids=()
    for t in dent scratch; do
        [ -f "$R/holdout-$t.json" ] || "$BIN/station" residual --model "$R/variation" --data "$DATA" --members 1 \
            --steps 3000 --second-look --holdout-type "$t" --out "$R/holdout-$t" & pids+=($!)
    done
    for p in "${pids[@]}"; do wait "$p"; done
}
timed holdout-pair pair
# the band network's training (make model's step 5 command, from scratch, 40 steps), one thread against two, alone
for th in 1 2; do
    [ -f "$R/thr$th/last.json" ] || timed "train-threads-$th" env OMP_NUM_THREADS="$th" "$BIN/station" train \
        --data "$DATA" --priors intensity,dolp,aolp --preset fast --fusion fused --batch-size 8 --seed 0 \
        --device cpu --roi band --size 96 --steps 40 --eval-every 40 --rendered-fraction 0.25 --out "$R/thr$th"
done
