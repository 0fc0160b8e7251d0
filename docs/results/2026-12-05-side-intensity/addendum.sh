#!/usr/bin/env bash
# plan.md's addendum: SI on seed 1196 with every edge chamfered 0.3 mm (e3) and rounded 0.3 mm without chips (r3),
# beside S and SA as the two-cameras-intensity study read them (reports copied). Resumable.
set -euo pipefail
HERE=$(cd "$(dirname "$0")" && pwd)
cd "$HERE/../../.."
R=runs/side-intensity
TWO=docs/results/2026-12-04-two-cameras-intensity
export OMP_NUM_THREADS=1
for pair in e3:chamfer03 r3:round03; do
    tag=${pair%%:*} name=${pair#*:}
    for f in line:line SA:side; do
        mkdir -p "$HERE/eval/${f%%:*}-$tag"
        cp "$TWO/eval/${f#*:}-1196-$tag/"{scores.csv,eval.json,eval.md} "$HERE/eval/${f%%:*}-$tag/"
    done
    [ -f "$HERE/eval/SI-$tag/scores.csv" ] || .venv/bin/station eval --model "$R/side" --data "data/sw-$name-1196" \
        --val-data data/sw-pv-val --presence-rule row_contrast --no-synthetic --no-plots --out "$HERE/eval/SI-$tag" \
        > "$R/eval-SI-$tag.log" 2>&1 &
done
wait
for tag in e3 r3; do
    for f in SA SI; do
        .venv/bin/station compare "$HERE/eval/line-$tag" "$HERE/eval/$f-$tag" --split "$HERE/split-$f.json" \
            --out "$R/pair-$f-$tag" > "$R/compare-$f-$tag.log" 2>&1
        for x in md json; do sed "s|$PWD/||g" "$R/pair-$f-$tag/two-cameras.$x" > "$HERE/pair-$f-$tag.$x"; done
    done
done
