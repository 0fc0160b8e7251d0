"""Screen: also hide each highlight's lobe, the pixels within REACH px of a core at or above CORE of full scale that
read at least FRAC of that core. Usage: PYTHONPATH=. python lobe.py CORE,REACH,FRAC ..."""

import sys

import cv2
import numpy as np
from common import load_val, report, scores

import model.draem.variation as V

shipped = V.VariationModel.highlight


def lobe(core_level: float, reach: int, frac: float):
    def highlight(peak: np.ndarray) -> np.ndarray:
        core = np.where(peak >= core_level, peak, 0).astype(np.float32)
        if not core.any():
            return shipped(peak)
        near = cv2.dilate(core, np.ones((2 * reach + 1,) * 2, np.uint8))  # the brightest core within reach
        return shipped(peak) | ((near > 0) & (peak >= frac * near))
    return staticmethod(highlight)


vm, x, lab, types, _ = load_val()
for spec in sys.argv[1:]:
    c, r, f = spec.split(",")
    V.VariationModel.highlight = lobe(float(c), int(r), float(f))
    print(report(spec, scores(vm, x)[0], lab, types), flush=True)
