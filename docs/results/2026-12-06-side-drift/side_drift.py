"""Is the second camera's drift monitor quiet on its line as built? (docs/results/2026-12-06-side-drift.md)

The side camera's frames of two small sets rendered for this: TRAIN drawn as `make side-model` draws its training set
(the panel's radiance, the finish and the edges varied: what its model's recorded frame statistics come from) and
BUILT the line as built (defects at 15 %). A ``DriftMonitor`` with TRAIN's range (as ``station variation`` records it:
``StatisticsRange.from_frames``) and the station's window, fed BUILT's frames in order: every warning it gives. Beside
it, the same frames against the line camera's shipped range (what a station reusing the first camera's range would
say). Run from the repository's root: ``python side_drift.py TRAIN BUILT``."""

import json
import sys

from model.draem.checkpoint import read_sidecar
from model.priors.frame_stats import StatisticsRange
from station.datasets import load_split
from station.drift import DriftMonitor, trained_range

train_dir, built_dir = sys.argv[1:3]
stats = {d: load_split(d, "val", ("intensity",), (64, 64), roi="center").frame_stats for d in (train_dir, built_dir)}
side = StatisticsRange.from_frames(stats[train_dir])
line = trained_range(read_sidecar("model/weights/default"))
print(f"side range from {len(stats[train_dir])} frames: {side.describe()}")
built = StatisticsRange.from_frames(stats[built_dir])
print(f"as built, {len(stats[built_dir])} frames: {built.describe()}")
print(f"line camera's shipped range: {line.describe()}")
out = {}
for name, rng in (("side range", side), ("line camera's range", line)):
    mon = DriftMonitor(rng, section="second_camera")
    said = [(i, t) for i, s in enumerate(stats[built_dir]) if (t := mon.update(s))]
    out[name] = {"warnings": [{"frame": i, "text": t} for i, t in said], "in_force_at_end": mon.warning}
    print(f"\n{name}: {len(said)} text(s)" + "".join(f"\n  frame {i}: {t}" for i, t in said))
json.dump(out, open(f"{sys.argv[3] if len(sys.argv) > 3 else 'side-drift'}.json", "w"), indent=1)
