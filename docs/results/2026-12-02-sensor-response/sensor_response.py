"""A copy of a set whose raws carry a real sensor's response: a black level pedestal, per-pixel gain
non-uniformity (PRNU), per-pixel polarizer angle errors with a finite extinction ratio, or all three.
Fixed patterns are drawn once from SEED, the same in every frame; everything but the raw is linked.

    python sensor_response.py SRC DST KIND SEED     KIND: pedestal64 | pedestal256 | prnu1 | polarizer | camera
"""
import json
import os
import sys
from pathlib import Path

import cv2
import numpy as np

from model.priors.mosaic import stokes_to_mosaic

PEDESTAL = 64          # codes of a 12-bit frame (1.6 % of full scale); pedestal256: 256 (6.25 %)
PRNU = 0.01            # sigma of each pixel's relative gain
ANGLE_DEG = 1.0        # sigma of each micro-polarizer's angle error
EXTINCTION = 100.0     # extinction ratio of every micro-polarizer

src, dst, kind, seed = Path(sys.argv[1]), Path(sys.argv[2]), sys.argv[3], int(sys.argv[4])
m = json.loads((src / "manifest.json").read_text())
h, w, full = m["height"], m["width"], 2 ** m["bit_depth"] - 1
rng = np.random.default_rng(seed)
gain = 1.0 + PRNU * rng.standard_normal((h, w))
delta = np.deg2rad(ANGLE_DEG) * rng.standard_normal((h, w))
e = (EXTINCTION - 1) / (EXTINCTION + 1)
zero, one = np.zeros((h, w), np.float32), np.ones((h, w), np.float32)
cos2t = 2 * stokes_to_mosaic(zero, one, zero)      # each pixel's nominal cos 2t, sin 2t
sin2t = 2 * stokes_to_mosaic(zero, zero, one)
cos2d, sin2d = np.cos(2 * delta), np.sin(2 * delta)
c_real = e * (cos2t * cos2d - sin2t * sin2d)       # cos 2(t + d), times e
s_real = e * (sin2t * cos2d + cos2t * sin2d)
PEDESTAL = 256 if kind == "pedestal256" else PEDESTAL
steps = {"pedestal64": ("pedestal",), "pedestal256": ("pedestal",), "prnu1": ("gain",), "polarizer": ("polarizer",),
         "camera": ("polarizer", "gain", "pedestal")}[kind]


def respond(raw: np.ndarray, gt: Path) -> np.ndarray:
    r = raw.astype(np.float64)
    if "polarizer" in steps:
        z = np.load(gt)
        r += 0.5 * ((c_real - cos2t) * z["s1"] + (s_real - sin2t) * z["s2"]) * full
    if "gain" in steps:
        r *= gain
    if "pedestal" in steps:
        r += PEDESTAL
    return np.clip(np.rint(r), 0, full).astype(raw.dtype)


(dst / "samples").mkdir(parents=True, exist_ok=True)
m["derived"] = (f"{src.name} with the sensor response {kind} ({', '.join(steps)}), patterns seed {seed} "
                "(sensor_response.py)")
(dst / "manifest.json").write_text(json.dumps(m, indent=1))
for d in sorted((src / "samples").iterdir()):
    o = dst / "samples" / d.name
    o.mkdir(exist_ok=True)
    for f in d.iterdir():
        if f.name.startswith("raw"):
            cv2.imwrite(str(o / f.name), respond(cv2.imread(str(f), cv2.IMREAD_UNCHANGED), d / "gt.npz"))
        elif not (o / f.name).exists():
            os.symlink(f.resolve(), o / f.name)
print(f"{dst}: {kind}")
