"""After the reads, a development check (the validation set, nothing chosen on it): does ECC's affine warp from the
identity fall short on the renders as it does on the unit tests' mottled parts? For each of the shipped file's
validation parts (``data/line-pv-val``), its correlation against a Euclidean (turn and shift) ECC fit and against the
affine fit started from that, matched away from highlights as ``VariationModel.register`` matches. Run from the
repository's root with ``PYTHONPATH=.``; its output is ecc_start.txt."""
import cv2
import numpy as np

from model.draem.checkpoint import load_checkpoint
from model.draem.frame_checks import MAX_HIDDEN
from station.datasets import load_split

ck = load_checkpoint("model/weights/default")
cfg, vm = ck.detector.config, ck.detector.variation
sp = load_split("data/line-pv-val", "val", cfg.priors, cfg.input_shape, roi=cfg.roi, frame_aspect=cfg.frame_aspect,
                dome_segments=cfg.dome_segments, around_px=cfg.around_px, progress=False)
ref = vm.reference.numpy()
CRITERIA = (cv2.TERM_CRITERIA_EPS | cv2.TERM_CRITERIA_COUNT, 50, 1e-4)  # as the model's ECC


def rho(moving: np.ndarray, mask: np.ndarray | None, motion: int, start: np.ndarray) -> tuple[float, np.ndarray]:
    """ECC's correlation and warp from ``start`` (-1 and the start when it fails)."""
    try:
        return cv2.findTransformECC(ref, moving, start.copy(), motion, CRITERIA, mask, 5)
    except cv2.error:
        return -1.0, start


rows = []
for xi, lab in zip(sp.priors.float().numpy(), sp.label.numpy(), strict=True):
    f = vm.features(xi, median=vm.log_median(xi))[vm.intensity]
    seen = ~vm.highlight(vm.peak(xi))
    mask = seen.astype(np.uint8) if seen.mean() > 1.0 - MAX_HIDDEN else None
    affine = rho(f, mask, cv2.MOTION_AFFINE, np.eye(2, 3, dtype=np.float32))[0]
    euclidean, m = rho(f, mask, cv2.MOTION_EUCLIDEAN, np.eye(2, 3, dtype=np.float32))
    rows.append((lab, affine, euclidean, rho(f, mask, cv2.MOTION_AFFINE, m)[0]))
r = np.array(rows, float)
for lab, name in ((0, "good"), (1, "defective")):
    s = r[r[:, 0] == lab]
    print(f"{name} parts {len(s)}: affine from the identity, median correlation {np.median(s[:, 1]):.4f}; "
          f"Euclidean above it by more than 0.002: {int((s[:, 2] - s[:, 1] > 0.002).sum())}; affine from the "
          f"Euclidean above it by more than 0.002: {int((s[:, 3] - s[:, 1] > 0.002).sum())}, at most by "
          f"{(s[:, 3] - s[:, 1]).max():.4f}")
