"""plan.md's degraded copies: a rendered set whose ground-truth normals carry a smooth random tilt error.

Each part's normals (camera frame, unit vectors) are turned by a field a = (a_x, a_y, 0): each component Gaussian
noise smoothed with a 10-px Gaussian (about 1 mm on the part), taken perpendicular to the normal and scaled so the
median angle between old and new normals over the part's pixels is LEVEL degrees. Its own stream per part,
``default_rng([round(10 * LEVEL), seed, index])``, so a part has the same field in every set it appears in.
Background pixels keep their normals. raw.png and params.json are linked, not copied; gt.npz is rewritten.
Resumable: a sample whose gt.npz exists is skipped.

Usage: python degrade.py LEVEL_DEG SRC OUT"""
import json
import sys
from pathlib import Path

import numpy as np
from scipy.ndimage import gaussian_filter

from sim.dataset import save_npz

level, src, out = float(sys.argv[1]), Path(sys.argv[2]), Path(sys.argv[3])
manifest = json.loads((src / "manifest.json").read_text())
manifest["normals_error_deg"] = level  # another set than SRC (its manifest hash differs)
(out / "samples").mkdir(parents=True, exist_ok=True)
(out / "manifest.json").write_text(json.dumps(manifest, indent=1))
medians = []
samples = sorted((src / "samples").iterdir())
for k, d in enumerate(samples):
    o = out / "samples" / d.name
    if (o / "gt.npz").exists():
        continue
    o.mkdir(exist_ok=True)
    for name in ("raw.png", "params.json"):
        if not (o / name).exists():
            (o / name).symlink_to((d / name).resolve())
    gt = dict(np.load(d / "gt.npz"))
    n, mask = gt["normal"].astype(np.float64), gt["object_mask"]
    rng = np.random.default_rng([round(10 * level), int(manifest["seed"]), int(d.name)])
    a = np.zeros_like(n)
    for c in (0, 1):
        a[..., c] = gaussian_filter(rng.standard_normal(mask.shape), 10.0)
    a -= (a * n).sum(-1, keepdims=True) * n  # perpendicular to the normal: a turn, not a stretch
    mag = np.linalg.norm(a, axis=-1)
    if mask.any():
        a *= np.tan(np.radians(level)) / np.median(mag[mask])
        turned = n + a
        turned /= np.maximum(np.linalg.norm(turned, axis=-1, keepdims=True), 1e-12)
        n = np.where(mask[..., None], turned, n)
        cos = np.clip((n * gt["normal"]).sum(-1), -1.0, 1.0)
        medians.append(float(np.degrees(np.median(np.arccos(cos[mask])))))
    gt["normal"] = n.astype(np.float32)
    tmp = o / "gt.tmp.npz"
    save_npz(tmp, gt)
    tmp.rename(o / "gt.npz")
    if k % 100 == 0:
        print(f"{out}: {k + 1}/{len(samples)}", flush=True)
if medians:
    print(f"{out}: median angular error per part {np.median(medians):.2f} deg "
          f"(range {min(medians):.2f}-{max(medians):.2f}) over {len(medians)} parts made now")
