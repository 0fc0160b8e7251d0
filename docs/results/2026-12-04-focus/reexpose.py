"""Re-expose a rendered set through a lens out of focus: each sample's stored exposed Stokes (gt.npz) through
``sim.sensor.lens_blur`` at SIGMA frame px (fireflies suppressed first), then the set's own polarizers and sensor with
the sample's own draws, as ../2026-11-29-sensor-optics/resensor.py re-exposes (raw.png new; gt.npz linked; params.json
and manifest.json copied). Resumable: a sample whose raw.png exists is kept.

    PYTHONPATH=. python reexpose.py SRC DST SIGMA"""
import json
import shutil
import sys
from dataclasses import replace
from pathlib import Path

import cv2
import numpy as np
from tqdm import tqdm

from sim.dataset import DatasetSpec
from sim.sensor import digitize, ideal_mosaic, lens_blur


def main(src: Path, dst: Path, sigma: float) -> None:
    manifest = json.loads((src / "manifest.json").read_text())
    spec = DatasetSpec.from_dict(manifest["config"])
    (dst / "samples").mkdir(parents=True, exist_ok=True)
    shutil.copy(src / "manifest.json", dst / "manifest.json")
    for d in tqdm(sorted((src / "samples").iterdir()), desc=f"blur {sigma} px", unit="sample"):
        out = dst / "samples" / d.name
        if (out / "raw.png").exists():
            continue
        out.mkdir(exist_ok=True)
        params = json.loads((d / "params.json").read_text())
        sensor = spec.sensor
        if "sensor" in params:
            sensor = replace(sensor, exposure_gain=params["sensor"]["exposure_gain"],
                             analog_gain=params["sensor"]["analog_gain"])
        with np.load(d / "gt.npz") as gt:
            s0, s1, s2 = lens_blur(gt["s0"], gt["s1"], gt["s2"], sigma)
        raw = digitize(ideal_mosaic(s0, s1, s2, sensor), sensor, np.random.default_rng([spec.seed, params["index"], 1]))
        shutil.copy(d / "params.json", out / "params.json")
        if not (out / "gt.npz").exists():
            (out / "gt.npz").symlink_to((d / "gt.npz").resolve())
        cv2.imwrite(str(out / "raw.png.tmp.png"), raw)
        (out / "raw.png.tmp.png").rename(out / "raw.png")


if __name__ == "__main__":
    main(Path(sys.argv[1]), Path(sys.argv[2]), float(sys.argv[3]))
