"""How far a part may move between the two frames of its set (rule-23 model C, `data/ps-val`), and what
`model.priors.photometric.frame_motion` reads for still parts. Run from the repository root:
    .venv/bin/python docs/results/2026-11-27-frame-sets/motion.py runs/ps/C-v data/ps-val motion.png > motion.json
Frame 2's Stokes images are shifted along x by sub-pixel amounts (bilinear; 0.5 px also blurs by half a pixel) before
the priors, as a part moving between exposures would shift them."""

import json
import sys

import cv2
import numpy as np

from model.priors import IMX250MZR
from model.priors.api import priors_from_stokes
from model.priors.demosaic import mosaic_to_stokes
from model.priors.mosaic import normalize_mosaic
from model.priors.photometric import frame_motion, mean_stokes, tilt_maps
from sim.dataset import open_dataset
from station.model_detector import DraemDetector


def shifted(a: np.ndarray, dx: float) -> np.ndarray:
    m = np.float32([[1, 0, dx], [0, 1, 0]])
    return cv2.warpAffine(a, m, (a.shape[1], a.shape[0]), flags=cv2.INTER_LINEAR, borderMode=cv2.BORDER_REPLICATE)


def main(model: str, data: str) -> dict:
    det = DraemDetector(model, device="cpu")
    names, segments = det.priors, det.dome_segments
    ds = open_dataset(data)
    bits = int(ds.manifest["bit_depth"])
    good_scores: dict[float, list[float]] = {}
    readings: dict[str, list[float]] = {}
    n_good = 0
    for i in ds.indices("val"):
        s = ds.load(i, ground_truth=False)
        kind = (s.params.get("defect") or {}).get("type", "defect") if s.label else "good"
        st = [mosaic_to_stokes(normalize_mosaic(r, bits).data, IMX250MZR, "bilinear", True) for r in s.raws]
        readings.setdefault(kind, []).append(frame_motion(st[0][0], st[1][0]))
        if s.label or n_good >= 60:
            continue
        n_good += 1
        for dx in (0.0, 0.25, 0.5, 1.0, 2.0):
            later = tuple(shifted(x, dx) for x in st[1])
            priors = priors_from_stokes(names, *mean_stokes([st[0], later]))
            priors.update(tilt_maps(names, segments, [st[0][0], later[0]]))
            good_scores.setdefault(dx, []).append(det.infer(priors).score)
    return {"model": model, "data": data, "threshold": det.threshold, "good_parts": n_good,
            "rejected_by_shift_px": {str(dx): float(np.mean(np.array(v) > det.threshold))
                                     for dx, v in good_scores.items()},
            "frame_motion_px_still_parts": {k: {"parts": len(v), "median": float(np.median(v)), "max": float(max(v))}
                                            for k, v in readings.items()}}


def plot(result: dict, path: str) -> None:
    """Good parts rejected against the shift between the frames, and the limit the station applies."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    shifts = [float(k) for k in result["rejected_by_shift_px"]]
    rejected = [100 * v for v in result["rejected_by_shift_px"].values()]
    fig, ax = plt.subplots(figsize=(5, 3.2))
    ax.plot(shifts, rejected, "o-")
    ax.axvline(0.5, color="k", ls=":", lw=0.8)
    ax.annotate("motion_limit (640 px)", (0.52, 50), fontsize=7)
    still = max(v["max"] for v in result["frame_motion_px_still_parts"].values())
    ax.axvspan(0, still, color="C2", alpha=0.15, lw=0)
    ax.annotate("frame_motion, still parts", (0.01, 80), fontsize=7, color="C2")
    ax.set(xlabel="shift between a part's two frames (px, 640 x 480)", ylabel="good parts rejected (%)",
           title=f"model C, {result['good_parts']} good validation parts")
    fig.savefig(path, dpi=120, bbox_inches="tight")
    plt.close(fig)


if __name__ == "__main__":
    result = main(sys.argv[1], sys.argv[2])
    if len(sys.argv) > 3:
        plot(result, sys.argv[3])
    print(json.dumps(result, indent=1))
