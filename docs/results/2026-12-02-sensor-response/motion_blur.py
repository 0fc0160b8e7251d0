"""A copy of a set whose raws show the part moving during the exposure: a box blur of LENGTH frame px along the
image's x axis, applied to each sample's exposed Stokes (gt.npz) and added to the raw as the ideal mosaic's
difference, so the renders' own noise draws are kept. Everything but the raw is linked.

    python motion_blur.py SRC DST LENGTH
"""
import json
import os
import sys
from pathlib import Path

import cv2
import numpy as np

from model.priors.mosaic import stokes_to_mosaic

src, dst, length = Path(sys.argv[1]), Path(sys.argv[2]), float(sys.argv[3])
m = json.loads((src / "manifest.json").read_text())
full = 2 ** m["bit_depth"] - 1
# the frame's pixels read between their centres by linear interpolation, averaged over a shift of -L/2..L/2:
# each tap is the mean over the shift of the interpolation's hat at that tap
shifts = np.linspace(-length / 2, length / 2, 2001)
n = int(np.ceil(length / 2))
taps = np.array([np.maximum(0.0, 1 - np.abs(shifts - k)).mean() for k in range(-n, n + 1)])
kernel = (taps / taps.sum()).reshape(1, -1).astype(np.float32)


def smear(a: np.ndarray) -> np.ndarray:
    return cv2.filter2D(a.astype(np.float32), -1, kernel, borderType=cv2.BORDER_REPLICATE)


(dst / "samples").mkdir(parents=True, exist_ok=True)
m["derived"] = f"{src.name} with a {length:g} px motion blur along image x (motion_blur.py)"
(dst / "manifest.json").write_text(json.dumps(m, indent=1))
for d in sorted((src / "samples").iterdir()):
    o = dst / "samples" / d.name
    o.mkdir(exist_ok=True)
    z = np.load(d / "gt.npz")
    s = [z["s0"], z["s1"], z["s2"]]
    delta = (stokes_to_mosaic(*[smear(x) for x in s]) - stokes_to_mosaic(*s)) * full
    for f in d.iterdir():
        if f.name == "raw.png":
            raw = cv2.imread(str(f), cv2.IMREAD_UNCHANGED)
            cv2.imwrite(str(o / f.name), np.clip(np.rint(raw + delta), 0, full).astype(raw.dtype))
        elif not (o / f.name).exists():
            os.symlink(f.resolve(), o / f.name)
print(f"{dst}: {length:g} px motion blur, kernel {np.round(kernel.ravel(), 3).tolist()}")
