#!/usr/bin/env bash
# The shipped file's own reports on the four fresh sets of plan.md (station eval, thresholds from the validation set),
# two at a time; resumable. Run from the repository's root.
set -euo pipefail
export OMP_NUM_THREADS=1
E=docs/results/2026-12-06-look-mean/eval
one() {  # one SET NAME [ARGS]
    [ -e "$E/$2/scores.csv" ] || .venv/bin/station eval --model model/weights/default --data "data/$1" \
        --val-data data/line-pv-val --no-synthetic --out "$E/$2" "${@:3}"
}
one look-built-1222 built & one look-new-kinds-1223 new-kinds & wait
one look-ggx-1224 ggx --no-plots & one look-rough-1224 rough --no-plots & wait
