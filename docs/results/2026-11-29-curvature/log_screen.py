"""Stop 59 screen: the variation model's window statistic (box mean of the largest channel's |z|, 5 px) against a
Laplacian of Gaussian of each channel's signed z (largest |response|, scale-normalised by sigma^2): a dent tilts the
surface, so its residual is a curvature, opposite across it, that a box of |z| averages with the noise around it.

For a model file's variation model, as ``zmaps`` computes z (clusters, noise level; no second look, no residual
network). Per-pixel location/spread (as the fit's ``_position``) from the even-numbered good parts of the val split
(A); each statistic's scores divided by its A 99th percentile (so that a max over statistics is fair); thresholds at
1 % and 5 % from the odd-numbered good parts (B). Selection on the val split (B good parts against its defective
parts); then each held-out set, thresholds held. Usage: python log_screen.py MODEL VAL OUT.json [HELDOUT...]

The calibration and scoring this script ran with were later moved, unchanged, into
../2026-11-29-ridge/window_screen.py (stop 60), which this script now calls. Rerun so on the validation set (stop 60,
model/weights/default), all 11 validation lines of screen.txt came out the same; only the width of the printed name
column changed."""
import sys
from pathlib import Path

import cv2
import numpy as np
from scipy.ndimage import gaussian_filter

sys.path.insert(0, str(Path(__file__).parent.parent / "2026-11-29-ridge"))
from window_screen import screen

SIGMAS = (1.5, 2.0, 2.5, 3.0, 4.0)


def stats(z, judged):
    o = {"abs5": cv2.blur(np.abs(z).max(0), (5, 5), borderType=cv2.BORDER_REPLICATE)}
    for s in SIGMAS:
        o[f"log{s}"] = s * s * np.max([np.abs(gaussian_filter(zc, s, order=(2, 0)) +
                                              gaussian_filter(zc, s, order=(0, 2))) for zc in z], 0)
    return o


screen(stats, lambda names: [(k,) for k in names] + [("abs5", f"log{s}") for s in SIGMAS])
