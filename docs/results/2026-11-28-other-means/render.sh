#!/bin/sh
# Rule 35's renders (run from the repository root; resumable). The same 400 parts as data/line-panel-heldout-1133
# (rule 33's render.sh), one change each: G GGX microfacets on the plastic, E the plastic's IOR 1.54.
set -e
V="--config sim/presets/line-polar.toml --config sim/presets/variation.toml --config sim/presets/panel.toml"
A="--count 400 --seed 1133 --defects 0.6 --heldout"
mkdir -p runs/om
two() {  # name, then station render's arguments: both shards, one per core
    name=$1; shift
    .venv/bin/station render "$@" --out data/$name --shard 0/2 > runs/om/$name-0.log 2>&1 &
    .venv/bin/station render "$@" --out data/$name --shard 1/2 > runs/om/$name-1.log 2>&1
    wait
}
two om-ggx $V $A --materials '{"plastic": {"type": "pplastic", "finish": "smooth", "distribution": "ggx"}}'
two om-ior $V $A --materials '{"plastic": {"type": "pplastic", "finish": "smooth", "int_ior": 1.54}}'
two om-rough $V $A --config docs/results/2026-11-28-other-means/rough.toml  # rule 36
