"""Re-expose a rendered set through another camera: the same scene Stokes (each sample's gt.npz), the same sensor
draws (params.json), one optical or sensor imperfection the shipped sets do not model. Writes a set station eval
reads (raw.png new; gt.npz linked; params.json and manifest.json copied).

    PYTHONPATH=. python resensor.py SRC DST KIND

KIND (each a plausible property of a real IMX250MZR camera with a C-mount lens):
  none      the set's own sensor (checks that this script reproduces raw.png byte for byte, and its formula)
  blur      lens blur: a Gaussian of sigma 0.7 px on the Stokes images before the polarizers
  vignette  relative illumination cos^4 falling to 0.80 at the frame's corners
  er100     extinction ratio 100 (the sets: ideal polarizers)
  angles    each pixel's polarizer turned by its own fixed error, SD 1 deg (one camera's pattern, seed 0)
  prnu      photo-response non-uniformity: each pixel's gain fixed at 1 + N(0, 0.01) (one camera's pattern)
  all       all five
"""

from __future__ import annotations

import json
import shutil
import sys
from dataclasses import replace
from pathlib import Path

import cv2
import numpy as np

from model.priors.conventions import get_layout
from sim.dataset import DatasetSpec
from sim.sensor import digitize, ideal_mosaic

KINDS = ("none", "blur", "vignette", "er100", "angles", "prnu", "all")


def camera_patterns(shape: tuple[int, int]) -> dict[str, np.ndarray]:
    """One camera's fixed patterns (the same for every frame): polarizer angle errors (rad) and pixel gains."""
    rng = np.random.default_rng(0)
    return {"angle_err": np.deg2rad(rng.normal(0.0, 1.0, shape)).astype(np.float32),
            "prnu": (1.0 + rng.normal(0.0, 0.01, shape)).astype(np.float32)}


def mosaic(s0: np.ndarray, s1: np.ndarray, s2: np.ndarray, layout: str, kind: str, pat: dict[str, np.ndarray]
           ) -> np.ndarray:
    """Exposed Stokes (full-scale units) -> noiseless mosaic I = 0.5 (S0 + e (S1 cos 2t + S2 sin 2t)), each pixel's
    t from the layout (plus its error), then the lens's illumination falloff and the pixel's gain."""
    every = kind == "all"
    if kind == "blur" or every:
        s0, s1, s2 = (cv2.GaussianBlur(s, (0, 0), 0.7) for s in (s0, s1, s2))
    h, w = s0.shape
    angles = np.deg2rad(np.asarray(get_layout(layout).angles_deg, dtype=np.float32))  # 2x2, row-major
    t = np.tile(angles.reshape(2, 2), (h // 2, w // 2))
    if kind == "angles" or every:
        t = t + pat["angle_err"]
    e = np.float32((100 - 1) / (100 + 1)) if kind == "er100" or every else np.float32(1.0)
    ideal = 0.5 * (s0 + e * (s1 * np.cos(2 * t) + s2 * np.sin(2 * t)))
    if kind == "vignette" or every:
        yy, xx = np.mgrid[0:h, 0:w].astype(np.float32)
        r = np.hypot(xx - (w - 1) / 2, yy - (h - 1) / 2) / np.hypot((w - 1) / 2, (h - 1) / 2)
        theta_corner = np.arccos(0.80 ** 0.25)  # cos^4 = 0.80 at r = 1
        ideal = ideal * np.cos(np.arctan(r * np.tan(theta_corner))) ** 4
    if kind == "prnu" or every:
        ideal = ideal * pat["prnu"]
    return ideal.astype(np.float32)


def main(src: Path, dst: Path, kind: str) -> None:
    assert kind in KINDS, kind
    manifest = json.loads((src / "manifest.json").read_text())
    spec = DatasetSpec.from_dict(manifest["config"])
    (dst / "samples").mkdir(parents=True, exist_ok=True)
    shutil.copy(src / "manifest.json", dst / "manifest.json")
    pat = camera_patterns((manifest["height"], manifest["width"]))
    same, gap = 0, 0.0
    dirs = sorted((src / "samples").iterdir())
    for d in dirs:
        out = dst / "samples" / d.name
        out.mkdir(exist_ok=True)
        params = json.loads((d / "params.json").read_text())
        sensor = spec.sensor
        if "sensor" in params:
            sensor = replace(sensor, exposure_gain=params["sensor"]["exposure_gain"],
                             analog_gain=params["sensor"]["analog_gain"])
        with np.load(d / "gt.npz") as gt:
            s0, s1, s2 = gt["s0"], gt["s1"], gt["s2"]
        if kind == "none":  # the renderer's own chain, and this script's formula checked against it
            ideal = ideal_mosaic(s0, s1, s2, sensor)
            gap = max(gap, float(np.abs(mosaic(s0, s1, s2, sensor.layout, kind, pat) - ideal).max()))
        else:
            ideal = mosaic(s0, s1, s2, sensor.layout, kind, pat)
        raw = digitize(ideal, sensor, np.random.default_rng([spec.seed, params["index"], 1]))
        if kind == "none":
            same += int(np.array_equal(raw, cv2.imread(str(d / "raw.png"), cv2.IMREAD_UNCHANGED)))
        cv2.imwrite(str(out / "raw.png"), raw)
        shutil.copy(d / "params.json", out / "params.json")
        if not (out / "gt.npz").exists():
            (out / "gt.npz").symlink_to((d / "gt.npz").resolve())
    if kind == "none":
        print(f"{same} of {len(dirs)} raw.png reproduced byte for byte; this script's mosaic differs from the "
              f"renderer's by at most {gap:.2e} full scale")


if __name__ == "__main__":
    main(Path(sys.argv[1]), Path(sys.argv[2]), sys.argv[3])
