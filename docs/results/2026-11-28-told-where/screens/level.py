"""Screen: hide highlights from a lower share of full scale (HIGHLIGHT_LEVEL), the shipped fit otherwise unchanged.
Usage: PYTHONPATH=. python level.py 1.0 0.9 0.8 0.7"""

import sys

import numpy as np
from common import load_val, report, scores

import model.draem.variation as V

vm, x, lab, types, _ = load_val()
for level in [float(a) for a in sys.argv[1:]]:
    V.HIGHLIGHT_LEVEL = level
    s, hid = scores(vm, x)
    good = lab == 0
    print(report(f"level {level}", s, lab, types),
          f"hidden (good) p50 {np.median(hid[good]):.3f} p90 {np.percentile(hid[good], 90):.3f}", flush=True)
