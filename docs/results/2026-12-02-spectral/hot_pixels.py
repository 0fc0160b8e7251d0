"""A copy of a set whose raws carry a sensor's hot pixels: K fixed positions (the same in every frame, drawn once from
SEED) at full scale, or raised by RISE of full scale (warm pixels), or at 0 (RISE "dead"). Everything else of each
sample is linked. python hot_pixels.py SRC DST K SEED [RISE|dead]"""
import json
import os
import sys
from pathlib import Path

import cv2
import numpy as np

src, dst, k, seed = Path(sys.argv[1]), Path(sys.argv[2]), int(sys.argv[3]), int(sys.argv[4])
dead = len(sys.argv) > 5 and sys.argv[5] == "dead"
rise = float(sys.argv[5]) if len(sys.argv) > 5 and not dead else None
m = json.loads((src / "manifest.json").read_text())
h, w, full = m["height"], m["width"], 2 ** m["bit_depth"] - 1
rng = np.random.default_rng(seed)
flat = rng.choice(h * w, size=k, replace=False)
ys, xs = np.unravel_index(flat, (h, w))
(dst / "samples").mkdir(parents=True, exist_ok=True)
how = "at 0 (dead)" if dead else "at full scale" if rise is None else f"raised by {rise:g} of full scale"
m["derived"] = f"{src.name} with {k} hot pixels {how}, fixed positions drawn with seed {seed} (hot_pixels.py)"
(dst / "manifest.json").write_text(json.dumps(m, indent=1))
(dst / "hot_pixels.json").write_text(json.dumps({"y": ys.tolist(), "x": xs.tolist()}))
for d in sorted((src / "samples").iterdir()):
    o = dst / "samples" / d.name
    o.mkdir(exist_ok=True)
    for f in d.iterdir():
        if f.name.startswith("raw"):
            r = cv2.imread(str(f), cv2.IMREAD_UNCHANGED)
            if dead:
                r[ys, xs] = 0
            elif rise is None:
                r[ys, xs] = full
            else:
                r[ys, xs] = np.minimum(r[ys, xs].astype(np.int64) + round(rise * full), full).astype(r.dtype)
            cv2.imwrite(str(o / f.name), r)
        elif not (o / f.name).exists():
            os.symlink(f.resolve(), o / f.name)
print(f"{dst}: {k} hot pixels {how}")
