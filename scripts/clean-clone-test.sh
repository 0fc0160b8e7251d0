#!/usr/bin/env bash
# What CI does, on this machine: clone HEAD into a temporary folder, run .ci/run there, print how long it took,
# and delete the clone (about 2.3 GB with its venv) whatever happens. CI shares this disk: a clone left behind
# once filled it, and CI then failed to install ("No space left on device").
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
dir="$(mktemp -d)"
trap 'rm -rf "$dir"' EXIT
git clone -q "$root" "$dir/clone"
echo "clean clone of $(git -C "$root" rev-parse --short HEAD) in $dir/clone; free: $(df -h --output=avail "$dir" | tail -1)"
start=$(date +%s)
status=0
"$dir/clone/.ci/run" || status=$?
echo "exit $status after $(( $(date +%s) - start )) s"
exit "$status"
