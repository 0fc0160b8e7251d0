"""screen.md and detail.md: the curvature window at several scales, each alone and each finer one with the largest,
on validation sets only. Calibration and scoring are ../2026-11-29-ridge/window_screen.py's (stop 60): per-pixel
median / 95th percentile of each statistic from the even good parts of VAL's val split (A), scores over their A 99th
percentile, thresholds at 1 % and 5 % from its odd good parts (B); VAL scored on B and its defective parts,
NEWKINDS_VAL:val on its val split.

Usage: [SIGMAS=1,1.5,2,3] python scale_screen.py MODEL VAL OUT.json NEWKINDS_VAL:val
SIGMAS (input px): the curvature's scales (default as screen.md)."""
import os
import sys
from pathlib import Path

import numpy as np
from scipy.ndimage import gaussian_filter

sys.path.insert(0, str(Path(__file__).parent.parent / "2026-11-29-ridge"))
from window_screen import screen

SIGMAS = tuple(float(s) for s in os.environ.get("SIGMAS", "1,1.5,2,3").split(","))


def stats(z: np.ndarray, judged: np.ndarray) -> dict[str, np.ndarray]:
    return {f"log{s}": s * s * np.max([np.abs(gaussian_filter(zc, s, order=(2, 0)) +
                                              gaussian_filter(zc, s, order=(0, 2))) for zc in z], 0)
            for s in SIGMAS}


screen(stats, lambda names: [(f"log{s}",) for s in SIGMAS] + [(f"log{s}", f"log{SIGMAS[-1]}") for s in SIGMAS[:-1]])
