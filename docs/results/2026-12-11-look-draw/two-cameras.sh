#!/usr/bin/env bash
# After ship.sh: the split of the two cameras' thresholds set again with the shipped file (the split's thresholds
# belong to the two files they were set with), and the pair read on seed 1245 as stop 127's two-camera study read it
# with the file before: the same side file and side evaluation (../2026-12-10-two-cameras-blend), the line file's
# evaluation of seed 1245 being the kept draw's (R2, ../2026-12-10-look-lens/eval/R2-built-1245), whose weights and
# threshold the shipped file has (checked below). Resumable; at nice 19.
set -euo pipefail
HERE=$(cd "$(dirname "$0")" && pwd)
cd "$HERE/../../.."
BIN=.venv/bin
R=runs/look-draw
echo 19 > /proc/self/autogroup 2>/dev/null || true
export OMP_NUM_THREADS=1
"$BIN/python" - <<'PY'
import json, sys
import torch
a, b = "model/weights/default", "runs/look-lens/R2"
x, y = (torch.load(f + ".pt", map_location="cpu", weights_only=True) for f in (a, b))
same = x.keys() == y.keys() and all(torch.equal(x[k].nan_to_num(1e30), y[k].nan_to_num(1e30)) for k in x) and \
    json.load(open(a + ".json"))["threshold"] == json.load(open(b + ".json"))["threshold"]
sys.exit(0 if same else "the shipped file is not R2: evaluate it on seed 1245 first")
PY
sha256sum runs/make-side-model/side.pt | cmp - docs/results/2026-12-10-two-cameras-blend/side.sha256
[ -f "$R/split.json" ] || "$BIN/station" split --model model/weights/default --data data/line-pv-val \
    --second-model runs/make-side-model/side --second-data data/sw-pv-val --out "$R/split.json" | tee "$HERE/split.txt"
cp "$R/split.json" "$HERE/split.json"
"$BIN/station" compare docs/results/2026-12-10-look-lens/eval/R2-built-1245 \
    docs/results/2026-12-10-two-cameras-blend/eval/side-1245 --split "$HERE/split.json" \
    --out "$R/two-cameras-1245" > "$R/compare.log" 2>&1
for x in md json; do cp "$R/two-cameras-1245/two-cameras.$x" "$HERE/two-cameras-1245.$x"; done
echo done
