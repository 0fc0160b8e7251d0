#!/usr/bin/env bash
# plan.md's sets B (seed 1222, as built), N (seed 1223, kinds nobody rendered), G and R (seed 1224, GGX and a duller
# plastic); resumable, two shards each; run from the repository's root.
set -euo pipefail
export OMP_NUM_THREADS=1
LINE=(--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml)
GGX='{"plastic": {"type": "pplastic", "finish": "smooth", "distribution": "ggx"}}'
two() {  # two OUT ARGS...: both shards of one set
    local out=$1; shift
    for k in 0 1; do .venv/bin/station render --out "$out" "${LINE[@]}" "$@" --shard "$k/2" & done
    wait
}
two data/look-built-1222 --count 400 --seed 1222 --defects 0.6 --heldout --visibility
two data/look-new-kinds-1223 --config sim/presets/new-kinds.toml --count 400 --seed 1223 --defects 0.6 --heldout \
    --visibility
two data/look-ggx-1224 --count 300 --seed 1224 --defects 0.3 --heldout --materials "$GGX"
two data/look-rough-1224 --count 300 --seed 1224 --defects 0.3 --heldout \
    --config docs/results/2026-11-28-other-means/rough.toml
