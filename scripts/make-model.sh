#!/usr/bin/env bash
# The shipped model, from nothing to model/weights/default, in one command: `make model` (or this script).
# Every step resumes: rerun it after an interruption and finished work is kept (renders per sample, training per
# checkpoint, the look networks every 250 steps). Sizes and steps are environment variables; the defaults are the
# shipped recipe on 2 CPU cores. Each command's wall time goes to RUNS/timings.tsv, summed per command at the end
# over every run (a resumed recipe's total). SHIP=0 stops before model/weights/ is replaced.
#
#   1. render the training set: line-polar preset + line variation + bright-field panel, its radiance drawn per
#      part (sim/presets/panel-vary.toml), the plastic's finish drawn wider (sim/presets/finish-vary.toml), each
#      part's edges chamfered 0-0.4 mm (EDGES; rule 67), defects in all splits (for mixed supervision)
#   2. render a held-out set with its own seed (every sample test, with the detectability oracle; the line as
#      built, panel constant), and with another seed two validation sets of the same parts (every sample val; 600
#      parts, ~370 good): one with the panel, the finish and the edges drawn as in training (calibration:
#      CALIBRATION), one with the panel drawn and the finish and edges as built (thresholds and selection: VAL)
#   3-5. the DRAEM networks. With DECISION=variation (the shipped recipe) they decide nothing and the station skips
#      them, so only a shell is trained: the band network, SHELL_STEPS steps from nothing, which carries the priors,
#      the band across the view and the input size (96 x 192) that steps 6-9 read (as the priors ablation's models;
#      docs/results/2026-12-04-intensity-ship.md). With another DECISION the networks decide and are trained whole:
#   3. base: good parts + DRAEM's synthetic anomalies (the paper's recipe), fused over PRIORS
#   4. mixed: the base fine-tuned with rendered defects in every batch (a quarter of it), synthetic ones kept
#   5. band: the mixed model fine-tuned on the band across the view at 96 x 192 (1.5x the centre square's detail)
#      (3-5 train with nothing beside them, on TRAIN_THREADS threads: every core)
#   6. variation: the registered variation model added (fitted on good train parts, calibrated on CALIBRATION;
#      with station variation's defaults: contrast divided out, 8 clusters, blurred copies, each place judged by the
#      curvature of its residual over 3 px, a second look's gate for the look network); the shipped model decides on
#      its finding alone (DECISION, chosen on the validation set: model/weights/README.md); station eval still
#      reports the networks, the station skips them
#   6b. look: one residual network (trained on the variation model's residuals of good parts with synthetic
#      anomalies and of the rendered defective parts) asked about the parts above the second look's gate, beside it
#      at each one's own 1 % threshold (station residual --second-look; rule 49, docs/results/2026-11-29-second-look.md;
#      with the curvature window and no test of its own since rule 60, docs/results/2026-11-29-curvature.md)
#   6b'. shape: the shape check (how far the part's bottom edge bends: a bowed part; rule 70,
#      docs/results/2026-12-05-moulding-kinds.md) and the outline check (a short step along its long edges: flash;
#      docs/results/2026-12-05-outline.md) added to the shipped model and to each look without a type, their
#      spread from the good train parts, their thresholds from CALIBRATION's good parts (station shape)
#   6b-draws. LOOK_DRAWS=K (default 3, since stop 128): the look trained K times (seeds 0..K-1), each finished as
#      below, and the one that rejects fewest good parts of the validation parts seen through a lens drawn per part
#      (LENS_VAL: VAL's parts rendered again with sim/presets/lens-vary.toml) kept as band-look (station pick; a
#      look's lens response is its training draw's: docs/results/2026-12-10-look-lens.md,
#      docs/results/2026-12-11-look-draw.md). The held-out types' looks are one draw each: the choice's tie-break
#      counts defects, the held-out type's among them
#   6b''. blend: each look asked about every part and blended with the window (BLEND of the window's finding, the
#      rest the network's, each over its own 1 % threshold on VAL's good parts, the checks' finding whole; in place;
#      station blend, docs/results/2026-12-07-blend-rates.md); BLEND=0 keeps the cascade of 6b
#   6c. threshold: the shipped model's threshold set again on VAL, the finish and edges as built (rules 63 and 67,
#      docs/results/2026-11-29-finish-vary.md, docs/results/2026-12-02-edge-range.md: the fit knows a range of
#      finishes and edges, the operating point is the line's)
#   7. held-out types: the shipped model without one type's rendered defects. With DECISION=variation (the shipped
#      recipe) the look network is the only part that learns from defects, so it is trained again without the type,
#      as in 6b and beside it, JOBS looks at once (each trains on one thread), and thresholded as in 6c (station
#      residual --holdout-type; the variation model never sees a defect).
#      With another DECISION the networks decide: they are trained without the type (from the base's last step) and
#      their variation model counts them (decision combined)
#   (6b-6c and 8 run JOBS at a time: each on one thread, two on 2 cores take the wall time of one)
#   8. evaluation on the held-out set (thresholds from validation), copy to model/weights/default (fp32 only: the
#      int8 networks of an earlier model scored a hostile frame across the threshold, see model/weights/README.md)
#   9. kinds nobody rendered: a held-out set of the line as built with blisters and particles only
#      (sim/presets/new-kinds.toml, its own seed), the shipped model evaluated on it (RUNS/eval-new-kinds-*, or
#      model/weights/default-eval-new-kinds when shipped); NEW_KINDS_COUNT=0 skips it
set -euo pipefail
cd "$(dirname "$0")/.."
BIN=${BIN:-.venv/bin}
DATA=${DATA:-data/line-ef-train}
HELDOUT=${HELDOUT:-data/line-panel-heldout}
VAL=${VAL:-data/line-pv-val}
CALIBRATION=${CALIBRATION:-data/line-ef-val}
RUNS=${RUNS:-runs/make-model}
TRAIN_COUNT=${TRAIN_COUNT:-900}
HELDOUT_COUNT=${HELDOUT_COUNT:-400}
HELDOUT_SEED=${HELDOUT_SEED:-1130}
NEW_KINDS=${NEW_KINDS:-data/new-kinds-heldout}
NEW_KINDS_COUNT=${NEW_KINDS_COUNT:-400}
NEW_KINDS_SEED=${NEW_KINDS_SEED:-1179}
VAL_COUNT=${VAL_COUNT:-600}
BASE_STEPS=${BASE_STEPS:-1000}
BASE_STOP=${BASE_STOP-500}  # the shipped base stopped its 1000-step schedule here (time); empty = run it all
MIXED_STEPS=${MIXED_STEPS:-400}
BAND_STEPS=${BAND_STEPS:-1200}
SHELL_STEPS=${SHELL_STEPS:-30}  # the band network's steps when it does not decide (DECISION=variation)
ROI=${ROI:-band}  # the region the model sees: band (96 x 192, the shipped file) or tall (SIZE=128: 128 x 192, room for
SIZE=${SIZE:-96}  # a turned camera, 3.4 points fewer caught: docs/results/2026-12-06-tall-band-recipe.md; the
# variation model's frame around the view, which station variation sets, keeps a 5-degree turn's good parts without
# it: docs/results/2026-12-06-view-margin.md)
BAND=(--roi "$ROI" --size "$SIZE")
HOLDOUT_STEPS=${HOLDOUT_STEPS:-150}
HOLDOUT_TYPES=${HOLDOUT_TYPES:-dent scratch stain chip missing_stud}
JOBS=${JOBS:-2}
SHIP=${SHIP:-1}
DECISION=${DECISION:-variation}
LOOK_MEMBERS=${LOOK_MEMBERS:-1}
LOOK_STEPS=${LOOK_STEPS:-3000}
BLEND=${BLEND:-0.25}  # the window's share of the look's blend (model.draem.residual.BLEND_WEIGHT); 0: the cascade
PRESET=(--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml)
VARY=(--config sim/presets/panel-vary.toml)  # training and validation only (rule 52)
FINISH=(--config sim/presets/finish-vary.toml)  # training and calibration only (rules 62-63)
EDGES=(--edge-mm 0,0.4)  # training and calibration only (rule 67): each part's chamfer drawn 0-0.4 mm
LENS=${LENS:-}  # a preset layered last on the training, calibration and validation sets (sim/presets/lens-vary.toml:
LENS_CONFIG=(${LENS:+--config "$LENS"})  # a lens drawn per part; docs/results/2026-12-08-lens-train/plan.md); "": none
SMOOTH_FIELD=${SMOOTH_FIELD:-0}  # 1: every variation fit takes a lens's smooth field out (station variation
SMOOTH=(); [ "$SMOOTH_FIELD" = 1 ] && SMOOTH=(--smooth-field)  # --smooth-field; docs/results/2026-12-09-smooth-field)
LOOK_LENS=${LOOK_LENS:-}  # LO,HI: every look network also learns from a lens copy of each good part (station residual
LOOK_LENS_ARGS=(${LOOK_LENS:+--lens-copies "$LOOK_LENS"})  # --lens-copies; docs/results/2026-12-10-look-lens); "": none
LOOK_DRAWS=${LOOK_DRAWS:-3}  # trainings of the look, the one a lens moves least kept (6b-draws); 1: one, seed 0
LENS_VAL=${LENS_VAL:-data/line-pv-val-lens}  # VAL's parts through a lens drawn per part: the draws' choice (6b-draws)
export OMP_NUM_THREADS=${OMP_NUM_THREADS:-1}  # one thread per process: see docs/platform-facts.md
TRAIN_THREADS=${TRAIN_THREADS:-$JOBS}  # the networks train alone, on every core: 1.6x one thread's speed on 2 cores
# the priors every network and the variation model read: the shipped file's intensity alone (since 2026-12-04:
# docs/results/2026-12-04-intensity-ship.md); PRIORS=intensity,dolp,aolp makes the file before's kind
PRIORS=${PRIORS:-intensity}
MODEL=(--priors "$PRIORS" --preset fast --fusion fused --batch-size 8 --seed 0 --device cpu)

mkdir -p "$RUNS"
TIMINGS="$RUNS/timings.tsv"  # one line per command: wall seconds, command, its output, when it ended (a rerun adds)
record() {  # record T0 COMMAND OUTPUT: the wall seconds since T0 (bash's $SECONDS) as one line of TIMINGS
    printf '%s\t%s\t%s\t%s\n' "$((SECONDS - $1))" "$2" "$3" "$(date -Is)" >> "$TIMINGS"
}
station() {  # station ARGS...: the command, timed under what it wrote (its --out, else its --model)
    local t0=$SECONDS out=- i j
    "$BIN/station" "$@"
    for ((i = 1; i < $#; i++)); do
        j=$((i + 1))
        case ${!i} in --out) out=${!j} ;; --model) [ "$out" = - ] && out=${!j} ;; esac
    done
    record "$t0" "$1" "$out"
}
train() {  # train ARGS...: station train on TRAIN_THREADS threads (nothing runs beside the networks' training)
    OMP_NUM_THREADS=$TRAIN_THREADS station train "$@"
}
render() {  # render OUT ARGS...: JOBS shards in parallel, each resumable
    local out=$1 t0=$SECONDS; shift
    local pids=()
    for ((k = 0; k < JOBS; k++)); do
        "$BIN/station" render --out "$out" "${PRESET[@]}" --shard "$k/$JOBS" "$@" & pids+=($!)
    done
    for p in "${pids[@]}"; do wait "$p"; done
    record "$t0" render "$out"
}

render "$DATA" "${VARY[@]}" "${FINISH[@]}" "${LENS_CONFIG[@]}" "${EDGES[@]}" --count "$TRAIN_COUNT" --seed 101 \
    --defects 0.4 --defects-in-train
render "$HELDOUT" --count "$HELDOUT_COUNT" --seed "$HELDOUT_SEED" --defects 0.6 --heldout --visibility
render "$CALIBRATION" "${VARY[@]}" "${FINISH[@]}" "${LENS_CONFIG[@]}" "${EDGES[@]}" --count "$VAL_COUNT" --seed 303 \
    --defects 0.4 --validation
VAL_ARGS=("${VARY[@]}" "${LENS_CONFIG[@]}" --count "$VAL_COUNT" --seed 303 --defects 0.4 --validation)
render "$VAL" "${VAL_ARGS[@]}"
if [ "$LOOK_DRAWS" -gt 1 ]; then  # 6b-draws: the same parts and draws as VAL, each through its own lens
    render "$LENS_VAL" "${VAL_ARGS[@]}" --config sim/presets/lens-vary.toml
fi
if [ "$NEW_KINDS_COUNT" -gt 0 ]; then
    render "$NEW_KINDS" --config sim/presets/new-kinds.toml --count "$NEW_KINDS_COUNT" --seed "$NEW_KINDS_SEED" \
        --defects 0.6 --heldout --visibility
fi

if [ "$DECISION" = variation ]; then  # steps 3-5: a shell (the networks do not decide)
    train --data "$DATA" "${MODEL[@]}" "${BAND[@]}" --steps "$SHELL_STEPS" --eval-every "$SHELL_STEPS" \
        --out "$RUNS/band"
    NETS=() BAND_NET=band/last
else
    train --data "$DATA" "${MODEL[@]}" --steps "$BASE_STEPS" ${BASE_STOP:+--stop-at-step "$BASE_STOP"} \
        --eval-every 100 --out "$RUNS/base"
    train --data "$DATA" "${MODEL[@]}" --steps "$MIXED_STEPS" --eval-every 100 \
        --rendered-fraction 0.25 --init "$RUNS/base/last" --out "$RUNS/mixed"
    train --data "$DATA" "${MODEL[@]}" "${BAND[@]}" --steps "$BAND_STEPS" --eval-every 200 \
        --rendered-fraction 0.25 --init "$RUNS/mixed/best" --out "$RUNS/band"
    NETS=(base/last mixed/best band/best) BAND_NET=band/best
fi
variation() {  # variation IN OUT [ARGS]: add the variation model unless OUT exists (resumable)
    [ -f "$2.json" ] || station variation --model "$1" --data "$DATA" --val-data "$CALIBRATION" --out "$2" \
        "${SMOOTH[@]}" "${@:3}"
}
shape() {  # shape NAME: the shape check added to RUNS/NAME in place, unless it has one (resumable)
    grep -qs '"outline": ' "$RUNS/$1.json" && return 0  # its sidecar's train.shape.outline (since stop 106)
    station shape --model "$RUNS/$1" --data "$DATA" --val-data "$CALIBRATION" --out "$RUNS/$1"
}
look() {  # look NAME [ARGS]: the look network added to band-variation as RUNS/NAME unless it exists (resumable)
    [ -f "$RUNS/$1.json" ] || station residual --model "$RUNS/band-variation" --data "$DATA" \
        --val-data "$CALIBRATION" --members "$LOOK_MEMBERS" --steps "$LOOK_STEPS" --second-look --out "$RUNS/$1" \
        "${LOOK_LENS_ARGS[@]}" "${@:2}"
}
blend() {  # blend NAME: the look of RUNS/NAME blended in place, unless it is (resumable)
    grep -qs '"blend": ' "$RUNS/$1.json" && return 0  # its sidecar's train.blend
    station blend --model "$RUNS/$1" --data "$VAL" --weight "$BLEND" --out "$RUNS/$1"
}
at_once() {  # at_once FUNCTION NAME...: FUNCTION NAME for each NAME, JOBS at a time, started in order (each on one
    local pids=() name p  # thread: two on 2 cores take the wall time of one); a failed one stops the recipe
    for name in "${@:2}"; do
        if [ "${#pids[@]}" -ge "$JOBS" ]; then wait "${pids[0]}"; pids=("${pids[@]:1}"); fi
        "$1" "$name" & pids+=($!)
    done
    for p in "${pids[@]}"; do wait "$p"; done
}
look_named() {  # look_named NAME: band-look, band-look-draw-N (seed N), or holdout-T without type T (steps 6b and 7)
    case $1 in
        band-look) look band-look ;;
        band-look-draw-*) look "$1" --seed "${1#band-look-draw-}" ;;
        *) look "$1" --holdout-type "${1#holdout-}" ;;
    esac
}
finish() {  # finish NAME: a look's checks (6b'), in place; its blend (6b''); its threshold on VAL (6c)
    shape "$1"
    [ "$BLEND" = 0 ] || blend "$1"
    station threshold --model "$RUNS/$1" --data "$VAL"
}
evaluate() {  # evaluate MODEL: station eval on the held-out set (step 8) into RUNS/eval-NAME
    local name=${1%/last}
    name=${name%/best}
    station eval --model "$RUNS/$1" --data "$HELDOUT" --val-data "$VAL" --out "$RUNS/eval-${name//\//-}"
}
variation "$RUNS/$BAND_NET" "$RUNS/band-variation" --decision "$DECISION"
SHIPPED=band-variation
HELD=()
if [ "$DECISION" = variation ]; then  # steps 6b-7: the look and the looks without each type, each finished
    SHIPPED=band-look
    for t in $HOLDOUT_TYPES; do HELD+=("holdout-$t"); done
    LOOKS=(band-look)
    if [ "$LOOK_DRAWS" -gt 1 ]; then
        LOOKS=(); for ((n = 0; n < LOOK_DRAWS; n++)); do LOOKS+=("band-look-draw-$n"); done
    fi
    at_once look_named "${LOOKS[@]}" "${HELD[@]}"
    at_once finish "${LOOKS[@]}" "${HELD[@]}"  # thresholded as the shipped model
    if [ "$LOOK_DRAWS" -gt 1 ] && [ ! -f "$RUNS/band-look.json" ]; then  # 6b-draws: the draw a lens moves least
        station pick --models "${LOOKS[@]/#/$RUNS/}" --data "$LENS_VAL" --out "$RUNS/band-look"
    fi
else
    station threshold --model "$RUNS/$SHIPPED" --data "$VAL"  # step 6c: the operating point of the line as built
    for t in $HOLDOUT_TYPES; do  # from the base's last step: keep-best there saw every type in validation
        train --data "$DATA" "${MODEL[@]}" "${BAND[@]}" --steps "$HOLDOUT_STEPS" \
            --eval-every "$HOLDOUT_STEPS" --rendered-fraction 0.25 --holdout-type "$t" --init "$RUNS/base/last" \
            --out "$RUNS/holdout-$t"
        variation "$RUNS/holdout-$t/best" "$RUNS/holdout-$t/variation" --decision combined  # the networks count
        HELD+=("holdout-$t/variation")
    done
fi

[ "${#NETS[@]}" = 0 ] || station threshold --model "$RUNS/base/last" --data "$DATA"
at_once evaluate "${NETS[@]}" band-variation ${SHIPPED/band-variation/} "${HELD[@]}"
station compare "$RUNS"/eval-* --out "$RUNS/compare"

if [ "$SHIP" = 1 ]; then
    "$BIN/python" -c "import sys; from model.draem.checkpoint import copy_checkpoint; copy_checkpoint(*sys.argv[1:])" \
        "$RUNS/$SHIPPED" model/weights/default
    station eval --model model/weights/default --data "$HELDOUT" --val-data "$VAL" \
        --out model/weights/default-eval
    cp "$RUNS"/compare/compare.* model/weights/default-eval/
fi
if [ "$NEW_KINDS_COUNT" -gt 0 ]; then  # step 9: the shipped model (the copy in model/weights when shipped)
    if [ "$SHIP" = 1 ]; then WHICH=(model/weights/default model/weights/default-eval-new-kinds)
    else WHICH=("$RUNS/$SHIPPED" "$RUNS/eval-new-kinds-$SHIPPED"); fi
    station eval --model "${WHICH[0]}" --data "$NEW_KINDS" --val-data "$VAL" --no-synthetic --out "${WHICH[1]}"
fi
echo "make model: wall time per command, summed over every run into $RUNS (one line each in $TIMINGS):"
awk -F'\t' '{s[$2] += $1; t += $1} END {for (c in s) printf "  %-10s %7.2f h\n", c, s[c] / 3600
    printf "  %-10s %7.2f h\n", "all", t / 3600}' "$TIMINGS"
