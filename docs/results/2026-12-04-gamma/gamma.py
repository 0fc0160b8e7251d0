"""A camera's tone curve on a rendered set: every raw.png code through code' = round(full x (code / full)^G), full the
set's largest code (raw.png new; gt.npz linked; params.json and manifest.json copied). Resumable.

    PYTHONPATH=. python gamma.py SRC DST G"""
import json
import shutil
import sys
from pathlib import Path

import cv2
import numpy as np


def main(src: Path, dst: Path, g: float) -> None:
    manifest = json.loads((src / "manifest.json").read_text())
    full = 2 ** manifest["bit_depth"] - 1
    lut = np.rint(full * (np.arange(full + 1) / full) ** g).astype(np.uint16)
    (dst / "samples").mkdir(parents=True, exist_ok=True)
    shutil.copy(src / "manifest.json", dst / "manifest.json")
    for d in sorted((src / "samples").iterdir()):
        out = dst / "samples" / d.name
        if (out / "raw.png").exists():
            continue
        out.mkdir(exist_ok=True)
        shutil.copy(d / "params.json", out / "params.json")
        if not (out / "gt.npz").exists():
            (out / "gt.npz").symlink_to((d / "gt.npz").resolve())
        raw = cv2.imread(str(d / "raw.png"), cv2.IMREAD_UNCHANGED)
        cv2.imwrite(str(out / "tmp.png"), lut[raw])
        (out / "tmp.png").rename(out / "raw.png")


if __name__ == "__main__":
    main(Path(sys.argv[1]), Path(sys.argv[2]), float(sys.argv[3]))
