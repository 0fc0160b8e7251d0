"""How fine a slope the stripes measure (the page's reading, as tilt-apart's tilt_error.py reads the dome halves):
on the first good parts of an F set, where the face mirrors the panel (the stripes' share a > A_MIN after
smoothing), the measured phase against the one the renderer's normal predicts. Both smoothed with a Gaussian of
10 frame px (about 1 mm, a dent flank's scale; the phase through its (c, s) pair); the prediction is a cubic in the
normal's three components fitted to exp(i phi) over all parts' pixels (what depends on the normal the same way on
every part, the camera's mount included on average). The error is the phase's difference from it, wrapped, read as
degrees of slope at 30 degrees of phase per degree (plan.md: 360 * 2 / 24). Normals from the line set's gt.npz
(the F set's own "normal" is the measurement).

Usage: PYTHONPATH=. python precision.py F_SET LINE_SET [PARTS [PHASE_PER_SLOPE [position]]]  (default 40 parts, 30
degrees of phase per degree of slope: the panel's stripes; plan-4's flat dome: 31.4). With "position" the prediction
also depends on the pixel's column (the cubic times (1, column)): a light at a finite distance (plan-4's flat dome,
0.30 m) is mirrored from where the face is, not only from its normal, as the panel (an environment map) is not."""
import sys

import numpy as np
from scipy.ndimage import gaussian_filter

from sim.dataset import open_dataset

A_MIN = 0.08


def good_parts(f_set, line_set, want):
    """The first ``want`` good parts' (z, n): z = c + i s, the measured pair, and n the renderer's normal (3
    components) with the pixel's column in [-1, 1], both smoothed at 10 px, where the face mirrors the light (the
    stripes' share > ``A_MIN``)."""
    parts = 0
    for i in f_set.indices("val") + f_set.indices("train"):
        s = f_set.load(i)
        if s.label:
            continue
        n = line_set.load(i).normal.astype(np.float64)
        mask = s.object_mask
        w = gaussian_filter(mask.astype(np.float64), 10.0)
        sm = [gaussian_filter(s.normal[..., k].astype(np.float64) * mask, 10.0) / np.maximum(w, 1e-9)
              for k in (0, 1)]
        nsm = np.stack([gaussian_filter(n[..., k] * mask, 10.0) / np.maximum(w, 1e-9) for k in range(3)], -1)
        where = mask & (w > 0.9) & (np.hypot(*sm) > A_MIN)
        column = np.broadcast_to(np.linspace(-1, 1, mask.shape[1]), mask.shape)[..., None]
        yield (sm[0] + 1j * sm[1])[where], np.concatenate([nsm, column], -1)[where]
        parts += 1
        if parts == want:
            return


def terms(n, position):
    """The prediction's terms: the cubic's 20 monomials in the normal's components, times (1, column) with
    ``position``."""
    x, y, v = n[:, 0], n[:, 1], n[:, 2]
    cubic = np.stack([x ** i * y ** j * v ** m for i in range(4) for j in range(4 - i) for m in range(4 - i - j)], 1)
    return np.concatenate([cubic, cubic * n[:, 3:4]], 1) if position else cubic


def slope_error(z, n, position, phase_per_slope):
    """Each pixel's phase against the least-squares prediction from ``terms``, wrapped, in degrees of slope."""
    t = terms(n, position).astype(np.complex128)
    beta = np.linalg.lstsq(t, z / np.abs(z), rcond=None)[0]
    return np.degrees(np.abs(np.angle(z * np.conj(t @ beta)))) / phase_per_slope


if __name__ == "__main__":
    PHASE_PER_SLOPE = float(sys.argv[4]) if len(sys.argv) > 4 else 360.0 * 2 / 24.0  # phase deg per slope deg
    f_set, line_set = open_dataset(sys.argv[1]), open_dataset(sys.argv[2])
    got = list(good_parts(f_set, line_set, int(sys.argv[3]) if len(sys.argv) > 3 else 40))
    z, n = np.concatenate([g[0] for g in got]), np.concatenate([g[1] for g in got])
    err = slope_error(z, n, len(sys.argv) > 5 and sys.argv[5] == "position", PHASE_PER_SLOPE)
    print(f"{sys.argv[1]}: {len(got)} good parts, {z.size} pixels where the face mirrors the panel (a > {A_MIN} at "
          f"10 px); slope error along the stripes at 10 px: median {np.median(err):.3f} deg, 90th percentile "
          f"{np.percentile(err, 90):.3f} deg")
