"""The outline check on parts rendered otherwise (not in the plan; a robustness reading, nothing chosen on it): the
shipped file before the check (runs/outline/B) and with it (runs/outline/S, now model/weights/default), each at its
threshold, on the sets the shipped file's robustness was read on (docs/limits.md, "Good parts rejected when rendered
differently"; rule 70's six): good parts rejected and defective parts caught, and which decisions changed. Run from
the repository's root; prints one line per set."""

import sys

import numpy as np

from model.draem.adapt import image_scores
from model.draem.checkpoint import load_checkpoint
from station.evaluation import model_split

SETS = {"1194 as built": "line-panel-heldout-1194", "1193 GGX": "ir-ggx-1193", "1193 duller": "ir-rough-1193",
        "1196 chamfered 0.3": "so-chamfer03-1196", "1196 rounded 0.3": "so-round03-1196",
        "1198 moulding": "moulding-1198", "1196 as built": "so-built-1196", "1196 lens blur 0.7": "so-blurff-1196",
        "1196 lens blur 1.0": "fo-blur10-1196", "1196 lens blur 1.5": "fo-blur15-1196",
        "1196 lens blur 2.0": "fo-blur20-1196", "1196 blur, vignetting, sensor": "so-allff-1196",
        "1196 30 hot pixels": "so-hot30-1196", "1196 pedestal 256": "so-pedestal256-1196",
        "1196 pedestal 256 stated": "so-pedestal256bl-1196", "1196 gamma 0.8": "ga-g08-1196",
        "1196 gamma 1.25": "ga-g125-1196", "1196 moving 2 px": "so-motion2-1196", "1196 moving 4 px": "so-motion4-1196",
        "1196 Mono8 camera": "so-camera-1196"}
files = {name: load_checkpoint(path) for name, path in (("B", "runs/outline/B"), ("S", "runs/outline/S"))}
for tag, data in SETS.items():
    if len(sys.argv) > 1 and tag not in sys.argv[1:]:
        continue
    sp = model_split(files["S"], "runs/outline/S", f"data/{data}", "test")
    judged = np.array([u is None for u in sp.unjudged]) if sp.unjudged else np.ones(len(sp.index), bool)
    x, label = sp.priors[judged], sp.label.numpy()[judged] == 1
    rejected = {}
    for name, ck in files.items():
        rejected[name] = image_scores(ck.detector, x) > ck.threshold
    b, a = rejected["B"], rejected["S"]
    types = np.array(sp.defect_type)[judged]
    changed = [f"{types[i] or 'good'}" for i in np.flatnonzero(a != b)]
    print(f"{tag:30s} good rejected {int(b[~label].sum())} -> {int(a[~label].sum())} of {int((~label).sum())}; "
          f"defective caught {int(b[label].sum())} -> {int(a[label].sum())} of {int(label.sum())}; "
          f"decisions changed: {len(changed)}{' (' + ', '.join(changed) + ')' if changed else ''}", flush=True)
