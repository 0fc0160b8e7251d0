"""plan.md's F sets: a line set's parts with the deflectometry frames' phase where the renderer's normals are kept.

Each part has three frames: the line's (the panel uniform, I_0) and two with the panel's stripes at phases 0 and 90
degrees (I_1, I_2; fringe-0.toml, fringe-90.toml), all else the same. With the panel's mean radiance kept, a pixel
reads I_k = I_0 + A cos(phi + theta_k), so the quadrature pair is c = (I_1 - I_0) / I_0 = a cos(phi) and
s = (I_0 - I_2) / I_0 = a sin(phi): phi the phase of the stripe the pixel's face mirrors (it moves by 360 * 2 t /
24 degrees for a slope t), a = A / I_0 the stripes' share of the pixel's light (0 where no face mirrors the panel).
S0 of each frame (bilinear demosaic, full frame), I_0 floored at 0.02 of full scale. The map (c, s, a) is written as
gt.npz's "normal", so the IN-G recipe (`station train --priors intensity,normal` without an estimator) reads it
unchanged; intensity comes from raw.png, the line's frame. A screen's device: a station would compute it as a prior.
raw.png and params.json are linked to the line set's, the other ground truth copied. Resumable (a sample whose
gt.npz exists is skipped); only parts present in all three sets are made.

Usage: python quadrature.py LINE_SET FRINGE0_SET FRINGE90_SET OUT"""
import json
import sys
from pathlib import Path

import numpy as np

from model.priors.api import set_stokes
from sim.dataset import open_dataset, save_npz

line, f0, f90, out = (Path(a) for a in sys.argv[1:5])
manifest = json.loads((line / "manifest.json").read_text())
manifest["deflectometry"] = [str(f0), str(f90)]  # another set than LINE (its manifest hash differs)
(out / "samples").mkdir(parents=True, exist_ok=True)
(out / "manifest.json").write_text(json.dumps(manifest, indent=1))
sets = [open_dataset(p) for p in (line, f0, f90)]
made = 0
for d in sorted((line / "samples").iterdir()):
    o = out / "samples" / d.name
    if (o / "gt.npz").exists() or not all((p / "samples" / d.name / "raw.png").exists() for p in (f0, f90)):
        continue
    i = int(d.name)
    o.mkdir(exist_ok=True)
    for name in ("raw.png", "params.json"):
        if not (o / name).exists():
            (o / name).symlink_to((d / name).resolve())
    raws = [s.load(i, ground_truth=False).raw for s in sets]
    _, stokes = set_stokes(raws, manifest["layout"], "bilinear", False, manifest["bit_depth"])
    i0, i1, i2 = (st[0].astype(np.float64) for st in stokes)
    floor = np.maximum(i0, 0.02)
    c, s = (i1 - i0) / floor, (i0 - i2) / floor
    gt = dict(np.load(d / "gt.npz"))
    gt["normal"] = np.stack([c, s, np.hypot(c, s)], -1).astype(np.float32)
    tmp = o / "gt.tmp.npz"
    save_npz(tmp, gt)
    tmp.rename(o / "gt.npz")
    made += 1
print(f"{out}: {made} parts made")
