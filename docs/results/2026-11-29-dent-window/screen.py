"""Stop 60 screen: dents, which the shipped window catches least of what the features separate (seed 1157: 74 % of
dents separable when told where, 44 % caught). Statistics of the signed z, against the shipped one (log3, the largest
channel's curvature at sigma 3):
  logS        the largest channel's curvature at sigma S (``model.draem.variation.curvature``), S in 2, 4, 5, 6;
  rssS        the root sum of squares of the channels' curvatures at sigma S: a dent tilts the surface, and a tilt
              shows in intensity and in both normalised Stokes components at once; the max of the channels reads one;
  and the larger of several scales (each divided by its good parts' 99th percentile).
Calibration and scoring: ../2026-11-29-ridge/window_screen.py.
Usage: python screen.py MODEL VAL OUT.json [HELDOUT...]"""
import sys
from pathlib import Path

import numpy as np

from model.draem.variation import curvature

sys.path.insert(0, str(Path(__file__).parent.parent / "2026-11-29-ridge"))
from window_screen import screen

SIGMAS = (2.0, 3.0, 4.0, 5.0, 6.0)


def stats(z, judged):
    o = {}
    for s in SIGMAS:
        c = np.stack([curvature(zc, s) for zc in z])
        o[f"log{s:g}"] = c.max(0)
        o[f"rss{s:g}"] = np.sqrt((c * c).sum(0))
    return o


screen(stats, lambda names: [(k,) for k in names] + [("log3", "log5"), ("log3", "log6"), ("log2", "log4", "log6"),
                                                     ("rss3", "rss5"), ("rss2", "rss4", "rss6"), ("log3", "rss3")])
