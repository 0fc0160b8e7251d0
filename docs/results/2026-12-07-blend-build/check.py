"""The built blend (``station blend``, ``model.draem.residual.blended``) against the rule plan 2 read
(../2026-12-07-ggx-train/screen.py ``Decisions.blend``, the shipped file's arrays), part for part: the two thresholds,
and each part's score (the built file's variation score over its window threshold against the screen's D). Prints the
largest difference per set and whether any decision at the screen's own D threshold differs.

Usage: python check.py BUILT DATA:SPLIT ... (run from the repository's root with PYTHONPATH=.)."""

import sys

import numpy as np
import torch

from model.draem.checkpoint import load_checkpoint
from model.draem.with_variation import rows
from station.datasets import load_split

sys.path.insert(0, "docs/results/2026-12-07-ggx-train")
from screen import Decisions, arrays  # the rule read on fresh seeds 1238-1239


def built_scores(model: str, path: str, split: str) -> np.ndarray:
    """(N,) the built file's variation scores (window units) on one split, as the station's detector gives them."""
    det = load_checkpoint(model).detector
    cfg = det.config
    sp = load_split(path, split, cfg.priors, cfg.input_shape, roi=cfg.roi, frame_aspect=cfg.frame_aspect,
                    dome_segments=cfg.dome_segments, around_px=cfg.around_px, progress=False)
    x, around = sp.priors.float(), None if sp.around is None else sp.around.float()
    out = []
    for i in range(0, len(x), 16):
        out.append(det.predict(x[i:i + 16], around=rows(around, i, 16)).member_scores["variation"].double().numpy())
    return np.concatenate(out)


def main(built: str, *sets: str) -> None:
    screen = Decisions("model/weights/default")
    weight, t_w, t_f = (float(v) for v in load_checkpoint(built).detector.residual.blend)
    print(f"thresholds: built t_w {t_w:.6f} t_f {t_f:.6f} weight {weight}; screen t_w {screen.t_w:.6f} "
          f"t_f {screen.t_f:.6f}")
    for arg in sets:
        path, split = arg.split(":")
        a = screen.blend(arrays(screen.model, arg))
        b = built_scores(built, path, split) / t_w
        d = np.abs(a - b)
        flips = int(((a > screen.thresholds["D"]) != (b > screen.thresholds["D"])).sum())
        print(f"{arg}: {len(a)} parts, largest |built - screen| {d.max():.2e} (relative {(d / np.abs(a)).max():.2e}); "
              f"decisions at the screen's D threshold that differ: {flips}", flush=True)


if __name__ == "__main__":
    torch.set_num_threads(1)
    main(*sys.argv[1:])
