"""After plan 3's read (nothing chosen on it): the registration's own turn on the first 30 parts of the 12, 20 and 30
degree sets. Each call of OpenCV's ECC (``VariationModel.warp_to``) is recorded: whether it converged, the angle and
scale of the affine warp it found. Run from the repository's root; prints why-T20.txt's lines."""
import cv2
import numpy as np

import model.draem.variation as variation
from model.draem.checkpoint import load_checkpoint
from station.datasets import load_split

det = load_checkpoint("model/weights/default").detector
cfg, var = det.config, det.variation
calls: list[np.ndarray | None] = []
ecc = cv2.findTransformECC


def recorded(*args, **kwargs):
    try:
        out = ecc(*args, **kwargs)
    except cv2.error:
        calls.append(None)
        raise
    calls.append(out[1].copy())
    return out


variation.cv2.findTransformECC = recorded
for turn, path in ((12, "data/turned12-1221"), (20, "data/turned20-1225"), (30, "data/turned30-1226")):
    sp = load_split(path, "test", cfg.priors, cfg.input_shape, roi=cfg.roi, frame_aspect=cfg.frame_aspect,
                    dome_segments=cfg.dome_segments, around_px=cfg.around_px, progress=False)
    calls.clear()
    var.zmaps(sp.priors[:30].float(), around=sp.around[:30].float())
    ok = [m for m in calls if m is not None]
    angle = [float(np.degrees(np.arctan2(m[1, 0], m[0, 0]))) for m in ok]
    scale = [float(np.hypot(*m[:, 0])) for m in ok]
    print(f"turned {turn} degrees: {len(calls)} warps, {len(calls) - len(ok)} not converged; the warp's turn median "
          f"{np.median(angle):.1f} degrees ({min(angle):.1f} to {max(angle):.1f}), scale {min(scale):.2f}-"
          f"{max(scale):.2f}")
