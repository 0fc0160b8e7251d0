"""Check 68's probe (plan.md): samples of data/sv-pv-val rendered again with [view] keys or the spp overridden,
every other draw the same. Saves each frame's S0 (full-scale units, 16-bit container), the rendered S0 before the
sensor (``truth``), the object mask and the camera-frame normals; prints the front face's high-pass spread (S0 less
its Gaussian blur of sigma 3 px, on the face's pixels eroded by 4 px, as a share of the face's mean level).

Usage (repository root):
    python docs/results/2026-11-30-wide-dome/probe.py TAG '{"flat_dome_width_m": 0.36}' 463,119 [OUT_DIR]
Writes OUT_DIR/TAG-INDEX.npz (default /tmp/probe). ``{}`` renders the stored sample again (identical to it).
"""

from __future__ import annotations

import copy
import json
import sys
import time
from pathlib import Path

import cv2
import numpy as np

from model.priors.demosaic import mosaic_to_stokes
from model.priors.mosaic import normalize_mosaic
from sim.dataset import DatasetSpec, generate_sample, prepare

SET = "data/sv-pv-val"


def face_spread(x: np.ndarray, mask: np.ndarray, normal: np.ndarray) -> float:
    """High-pass spread of ``x`` on the front faces (camera-frame normal z > 0.95: turned under 18 degrees), %
    of their mean."""
    face = cv2.erode(((mask > 0) & (normal[..., 2] > 0.95)).astype(np.uint8), np.ones((9, 9), np.uint8)) > 0
    hp = x - cv2.GaussianBlur(x, (0, 0), 3)
    return float(100 * hp[face].std() / x[face].mean())


def main() -> None:
    tag, over, indices = sys.argv[1], json.loads(sys.argv[2]), [int(a) for a in sys.argv[3].split(",")]
    out = Path(sys.argv[4] if len(sys.argv) > 4 else "/tmp/probe")
    out.mkdir(parents=True, exist_ok=True)
    cfg = copy.deepcopy(json.loads(Path(SET, "manifest.json").read_text())["config"])
    for k, v in over.items():
        if k == "spp":
            cfg["spp"] = v
        else:
            cfg["view"][k] = v
    spec = DatasetSpec.from_dict(cfg)
    model = prepare(spec)
    for i in indices:
        t = time.time()
        s = generate_sample(spec, model, i)
        s0, _, _ = mosaic_to_stokes(normalize_mosaic(s.raw).data)
        np.savez_compressed(out / f"{tag}-{i}.npz", s0=s0, mask=s.object_mask, normal=s.normal, truth=s.s0)
        print(f"{tag} {i}: {time.time() - t:.1f} s; face high-pass spread: frame "
              f"{face_spread(s0, s.object_mask, s.normal):.2f} %, rendered "
              f"{face_spread(s.s0, s.object_mask, s.normal):.2f} %", flush=True)


if __name__ == "__main__":
    main()
