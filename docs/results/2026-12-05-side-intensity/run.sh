#!/usr/bin/env bash
# plan.md: the side camera with intensity alone (SI) against the side file as it stands (SA). Run from anywhere;
# resumable (renders per sample, make side-model per step, a finished report is kept). STEP=make|read|all (default).
set -euo pipefail
HERE=$(cd "$(dirname "$0")" && pwd)
cd "$HERE/../../.."
BIN=.venv/bin
R=runs/side-intensity
mkdir -p "$R" "$HERE/eval"
export OMP_NUM_THREADS=1
STEP=${STEP:-all}
if [ "$STEP" = make ] || [ "$STEP" = all ]; then
    # SI: make side-model with the shipped intensity-only file's networks as its source: its band network before the
    # variation model and look were added (runs/make-model-r/band/last, from the make-model run whose band-look is the
    # shipped file, weights 88e03190); station variation --refit refuses a file with residual networks. Then the side
    # twins of seed 1193's renders.
    if [ ! -f "$R/source/default.json" ]; then
        mkdir -p "$R/source"
        "$BIN/python" -c "import sys; from model.draem.checkpoint import copy_checkpoint; copy_checkpoint(*sys.argv[1:])" \
            runs/make-model-r/band/last "$R/source/default"
    fi
    RUNS=$R OUT=$R/side make side-model > "$R/make-side-model.log" 2>&1 & fit=$!
    V=(--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml
       --count 400 --seed 1193 --defects 0.3 --heldout)
    SIDE=(--config sim/presets/side-view.toml)  # last, as every side twin
    GGX='{"plastic": {"type": "pplastic", "finish": "smooth", "distribution": "ggx"}}'
    "$BIN/station" render --out data/sw-ggx-1193 "${V[@]}" --materials "$GGX" "${SIDE[@]}" > "$R/render-ggx.log" 2>&1 &
    a=$!
    "$BIN/station" render --out data/sw-rough-1193 "${V[@]}" --config docs/results/2026-11-28-other-means/rough.toml \
        "${SIDE[@]}" > "$R/render-rough.log" 2>&1 & b=$!
    wait $fit; wait $a; wait $b
fi
judge() {  # judge CAMERA FILE SET TAG VAL [ARGS]: one report into eval/TAG
    local out="$HERE/eval/$4"
    [ -f "$out/scores.csv" ] && return
    "$BIN/station" eval --model "$2" --data "data/$3" --val-data "data/$5" --no-synthetic --no-plots --out "$out" \
        "${@:6}" > "$R/eval-$4.log" 2>&1
}
if [ "$STEP" = read ] || [ "$STEP" = all ]; then
    TWO=docs/results/2026-12-04-two-cameras-intensity
    cp "$TWO/split.json" "$HERE/split-SA.json"
    for seed in 1196 1197; do  # as built: S and SA read by the two-cameras study, copied
        for tag in line side; do
            mkdir -p "$HERE/eval/$tag-$seed"
            cp "$TWO/eval/$tag-$seed/"{scores.csv,eval.json,eval.md} "$HERE/eval/$tag-$seed/"
        done
        rm -rf "$HERE/eval/SA-$seed"; mv "$HERE/eval/side-$seed" "$HERE/eval/SA-$seed"
    done
    for set in ggx rough; do  # S and SA on seed 1193 rendered otherwise, while SI is made (STEP=read beside make)
        judge line model/weights/default "ir-$set-1193" "line-$set" line-pv-val &
        judge side runs/make-side-model/side "sw-$set-1193" "SA-$set" sw-pv-val --presence-rule row_contrast
        wait
    done
    while [ ! -f "$R/split.json" ]; do sleep 30; done  # make side-model's last step
    cp "$R/split.json" "$HERE/split-SI.json"
    judge side "$R/side" sw-heldout-1196 SI-1196 sw-pv-val --presence-rule row_contrast &
    judge side "$R/side" sw-heldout-1197 SI-1197 sw-pv-val --presence-rule row_contrast
    wait
    judge side "$R/side" sw-ggx-1193 SI-ggx sw-pv-val --presence-rule row_contrast &
    judge side "$R/side" sw-rough-1193 SI-rough sw-pv-val --presence-rule row_contrast
    wait
    for tag in 1196 1197 ggx rough; do
        for f in SA SI; do
            "$BIN/station" compare "$HERE/eval/line-$tag" "$HERE/eval/$f-$tag" --split "$HERE/split-$f.json" \
                --out "$R/pair-$f-$tag" > "$R/compare-$f-$tag.log" 2>&1
            for x in md json; do  # paths from the repository's root, as the reports are read
                sed "s|$PWD/||g" "$R/pair-$f-$tag/two-cameras.$x" > "$HERE/pair-$f-$tag.$x"
            done
        done
    done
fi
if [ "$STEP" = read ] || [ "$STEP" = all ]; then  # the addenda's sets too (plan.md), then the reading
    "$HERE/addendum.sh"
    "$HERE/addendum2.sh"
    (cd "$HERE" && PYTHONPATH=../../.. ../../../.venv/bin/python read.py > read.txt)
fi
