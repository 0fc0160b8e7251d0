"""Rule 53's training and validation sets without rendering them again: the same scenes (each sample's gt.npz, the
exposed scene Stokes) through the sensor chain `station render` runs (sim.sensor: the lens, polarizers, noise,
ADC, the noise stream [seed, index, 1]), with the sensor drawn by the new set's [variation]. `--check N` renders N
samples with `station render`'s own code and compares them byte for byte first.

    PYTHONPATH=. python expose53.py SRC DST LAYER.toml [--check N]
"""

from __future__ import annotations

import json
import sys
import tempfile
from pathlib import Path

import cv2
import numpy as np

from sim import dataset as sd
from sim.sensor import digitize, ideal_mosaic, lens


def new_spec(src: Path, layer: Path) -> sd.DatasetSpec:
    config = json.loads((src / "manifest.json").read_text())["config"]
    extra = sd.read_overrides(layer)
    config["variation"] = {**config.get("variation", {}), **extra.get("variation", {})}
    assert set(extra) == {"variation"}, "only [variation] keys change the sensor alone"
    return sd.DatasetSpec.from_dict(config)


def expose(spec: sd.DatasetSpec, d: Path, index: int) -> tuple[np.ndarray, dict]:
    params = json.loads((d / "params.json").read_text())
    sensor, record = spec.variation.draw(spec.sensor, spec.seed, index)
    assert {k: params["sensor"][k] for k in ("exposure_scale", "analog_gain")} == \
        {k: record[k] for k in ("exposure_scale", "analog_gain")}, d
    with np.load(d / "gt.npz") as gt:
        s = (gt["s0"], gt["s1"], gt["s2"])
    raw = digitize(ideal_mosaic(*lens(*s, sensor), sensor), sensor,
                   np.random.default_rng([spec.seed, index, 1]))
    return raw, {**params, "sensor": record}


def check(spec: sd.DatasetSpec, src: Path, n: int) -> None:
    model = sd.prepare(spec)
    for index in range(n):
        rendered = sd.generate_sample(spec, model, index)
        raw, params = expose(spec, sd.sample_dir(src, index), index)
        assert np.array_equal(raw, rendered.raw), index
        assert params["sensor"] == rendered.params["sensor"], index
        print(f"sample {index}: byte for byte as station render, lens blur {params['sensor']['lens_blur_px']:.3f} px")


def main(src: Path, dst: Path, layer: Path, n_check: int) -> None:
    spec = new_spec(src, layer)
    if n_check:
        check(spec, src, n_check)
    manifest = json.loads((src / "manifest.json").read_text())
    manifest["config"] = spec.to_dict()
    (dst / "samples").mkdir(parents=True, exist_ok=True)
    (dst / "manifest.json").write_text(json.dumps(manifest, indent=1))
    for index in range(manifest["count"]):
        d, out = sd.sample_dir(src, index), sd.sample_dir(dst, index)
        if (out / "params.json").is_file():
            continue  # resumable
        raw, params = expose(spec, d, index)
        tmp = Path(tempfile.mkdtemp(dir=dst / "samples"))
        cv2.imwrite(str(tmp / "raw.png"), raw)
        (tmp / "gt.npz").symlink_to((d / "gt.npz").resolve())
        (tmp / "params.json").write_text(json.dumps(params, indent=1))
        tmp.rename(out)
    print(f"{dst}: {manifest['count']} samples")


if __name__ == "__main__":
    args = sys.argv[1:]
    n = int(args[args.index("--check") + 1]) if "--check" in args else 0
    main(Path(args[0]), Path(args[1]), Path(args[2]), n)
