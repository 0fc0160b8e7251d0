"""Screen (stop 58, not a rule): the variation model's projection on its components fitted twice, the second time
without the pixels whose first-pass residual exceeds LIMIT scales in any channel (a local defect should not pull the
line's components). Runs `station eval` with the patch. Usage: PYTHONPATH=. python robust.py LIMIT -- eval args"""
import sys

import numpy as np

from model.draem import variation as V

LIMIT = float(sys.argv[1])
orig = V.VariationModel._judged_residual


def judged_residual(self, xi):
    mean, part = self.mean.numpy(), self.region.numpy()
    warped, judged, where = self._aligned(xi)
    warped[:-1], k = self.align_contrast(warped[:-1], where)
    hidden = 1.0 - judged.sum() / max(part.sum(), 1)
    if judged.sum() < (1.0 - V.MAX_HIDDEN) * part.sum():
        judged = part
    u = (warped[:-1] - mean) / self.channel_scale.numpy()[:, None, None] * part
    comps, scale = self.components.numpy(), self.scale.numpy()
    r, coef = self._residual(u[None], comps, judged)
    z = np.abs(r[0]) / scale
    keep = judged & (z.max(0) <= LIMIT)
    if keep.sum() >= 0.5 * judged.sum():
        r, coef = self._residual(u[None], comps, keep)
    r = r[0]
    r[self.intensity] *= k
    return r / scale, coef[0], judged, float(hidden)


V.VariationModel._judged_residual = judged_residual
from station.cli import main  # noqa: E402

sys.exit(main(sys.argv[3:]))
