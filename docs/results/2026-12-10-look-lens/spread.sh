#!/usr/bin/env bash
# plan.md's addendum: R1 and R2 (the control R with seeds 1 and 2), read on B and V. Resumable; at nice 19.
set -euo pipefail
HERE=$(cd "$(dirname "$0")" && pwd)
cd "$HERE/../../.."
BIN=.venv/bin
R=runs/look-lens
echo 19 > /proc/self/autogroup 2>/dev/null || true
export OMP_NUM_THREADS=1 PYTHONPATH=.
arm() {  # arm NAME SEED: as make-a.sh's R, with its own seed
    [ -f "$R/$1.done" ] && return
    [ -f "$R/$1.json" ] || "$BIN/station" residual --model "$R/s-variation" --data data/line-ef-train \
        --val-data data/line-ef-val --members 1 --steps 3000 --second-look --seed "$2" --out "$R/$1" > "$R/$1.log" 2>&1
    "$BIN/station" blend --model "$R/$1" --data data/line-pv-val --weight 0.25 --out "$R/$1" >> "$R/$1.log" 2>&1
    "$BIN/station" threshold --model "$R/$1" --data data/line-pv-val >> "$R/$1.log" 2>&1
    touch "$R/$1.done"
}
judge() {  # judge ARM SET
    local out="$HERE/eval/$1-$2" data=data/ll-$2
    [ "$2" = built-1245 ] && data=data/line-heldout-1245
    [ -f "$out/eval.md" ] || "$BIN/station" eval --model "$R/$1" --data "$data" --val-data data/line-pv-val \
        --no-synthetic --no-plots --out "$out" > "$R/eval-$1-$2.log" 2>&1
}
arm R1 1 & a=$!
arm R2 2; wait $a
for s in built-1245 allff-1245; do judge R1 "$s" & a=$!; judge R2 "$s"; wait $a; done
"$BIN/python" - <<'PY' > "$HERE/spread.txt"
import sys
sys.path.insert(0, "docs/results/2026-12-10-look-lens")
from read import lens_train
print("| file | B: good rejected | B: caught | V: good rejected | V: caught |\n|---|---|---|---|---|")
for m in ("S", "R", "R1", "R2"):
    row = [m]
    for name in ("built-1245", "allff-1245"):
        d = lens_train.load(m, name)
        y, rej = d["label"], d["score"] > d["threshold"]
        row += [f"{int(rej[y == 0].sum())} of {int((y == 0).sum())}", f"{rej[y == 1].mean():.1%}"]
    print("| " + " | ".join(row) + " |")
PY
echo done
