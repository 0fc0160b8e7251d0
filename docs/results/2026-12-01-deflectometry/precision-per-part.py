"""After plan-4's reading, not deciding: precision.py's slope error with the prediction fitted on each part alone (the
cubic in the normal times (1, column), 40 coefficients per part) instead of one prediction for all parts. What is
left is the measurement's own scatter at 1 mm on a face that mirrors the light, with what differs from part to part
(its pose, its distance from the camera) taken out, as a variation model's components take out a global turn.

Usage: PYTHONPATH=. python precision-per-part.py F_SET LINE_SET PHASE_PER_SLOPE [PARTS]  (default 20 parts)"""
import sys

import numpy as np
from precision import good_parts, slope_error

from sim.dataset import open_dataset

f_set, line_set = open_dataset(sys.argv[1]), open_dataset(sys.argv[2])
errs, shares = [], []
for z, n in good_parts(f_set, line_set, int(sys.argv[4]) if len(sys.argv) > 4 else 20):
    errs.append(slope_error(z, n, True, float(sys.argv[3])))
    shares.append(np.median(np.abs(z)))
err = np.concatenate(errs)
print(f"{sys.argv[1]}: {len(errs)} good parts, each part's own prediction; slope error along the stripes at 10 px: "
      f"median {np.median(err):.3f} deg, 90th percentile {np.percentile(err, 90):.3f} deg; the stripes' share a: "
      f"median {np.median(shares):.2f}")
