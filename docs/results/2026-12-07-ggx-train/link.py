"""The GGX training set's parts whose lobe stays Beckmann, linked from data/line-ef-train-900 (a sample depends only
on the seed and its index, and the lobe's draw has its own stream: sim/dataset.py draw_sample), so that `station
render` renders only the parts the draw gives a GGX lobe. Prints how many it linked.

Usage: python link.py SOURCE OUT SHARE (run from the repository's root)."""

import json
import sys
from pathlib import Path

import numpy as np

source, out, share = Path(sys.argv[1]), Path(sys.argv[2]), float(sys.argv[3])
manifest = json.loads((source / "manifest.json").read_text())
seed, count = manifest["seed"], manifest["count"]
(out / "samples").mkdir(parents=True, exist_ok=True)
linked = 0
for index in range(count):
    if np.random.default_rng([seed, index, 7]).random() >= share:
        target = (source / "samples" / f"{index:06d}").resolve()
        link = out / "samples" / f"{index:06d}"
        if not link.exists():
            link.symlink_to(target)
        linked += 1
print(f"linked {linked} of {count} parts (Beckmann); {count - linked} to render with a GGX lobe")
