# Sourced by run.sh, addendum.sh and addendum2.sh: this folder's paths and presets, and its reading's three steps. Each
# step keeps a finished report (rerun a script after an interruption).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/../../.."  # the repository root
R=runs/c98
D=docs/results/2026-12-04-side-edges
mkdir -p $R $D/eval
export OMP_NUM_THREADS=1
P=(--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml)
S=(--config sim/presets/side-view.toml)  # last: the side camera and its flat dome
E=(--no-synthetic --no-plots)
line() {  # line SET TAG: the shipped line file on SET (thresholds from data/line-pv-val) as R/eval-line-TAG
    [ -f "$R/eval-line-$2/scores.csv" ] || .venv/bin/station eval --model model/weights/default --data "$1" \
        --val-data data/line-pv-val "${E[@]}" --out "$R/eval-line-$2" > "$R/eval-line-$2.log" 2>&1
    cp "$R/eval-line-$2/eval.md" "$D/eval/eval-line-$2.md"
}
side() {  # side SET TAG: the side file on SET (thresholds from data/sw-pv-val) as R/eval-side-TAG
    [ -f "$R/eval-side-$2/scores.csv" ] || .venv/bin/station eval --model runs/make-side-model/side --data "$1" \
        --val-data data/sw-pv-val --presence-rule row_contrast "${E[@]}" --out "$R/eval-side-$2" \
        > "$R/eval-side-$2.log" 2>&1
    cp "$R/eval-side-$2/eval.md" "$D/eval/eval-side-$2.md"
}
ablation_line() {  # ablation_line SEED: the shipped file's report on data/line-heldout-SEED as the priors ablation read it
    mkdir -p "$R/eval-line-$1"
    cp "$D/../2026-12-04-priors-ablation/shipped/eval-E63-$1/scores.csv" \
       "$D/../2026-12-04-priors-ablation/shipped/eval-E63-$1/eval.json" "$R/eval-line-$1/"
}
pair() {  # pair TAG: the two cameras at make side-model's split on R/eval-line-TAG and R/eval-side-TAG, into D
    .venv/bin/station compare "$R/eval-line-$1" "$R/eval-side-$1" --split runs/make-side-model/split.json \
        --out "$R/two-cameras-$1"
    cp "$R/two-cameras-$1/two-cameras.md" "$D/two-cameras-$1.md"
    cp "$R/two-cameras-$1/two-cameras.json" "$D/two-cameras-$1.json"
}
