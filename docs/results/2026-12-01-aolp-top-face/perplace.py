"""The AoLP statistic judged per place in frame coordinates (no registration): Im q / sqrt(S0) within the top-face
prior, Gaussian-averaged at SIG px, against the median and robust spread of 300 good training parts at each pixel;
the score is the largest magnitude over the prior > 0.5 (validation screen).

    PRIOR=0.5 python perplace.py data/line-pf-train data/line-pv-val val303-perplace.json
"""
import json
import os
import sys
from concurrent.futures import ProcessPoolExecutor

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import aolp_screen as a

SIG = float(os.environ.get("SIG", "5.0"))


def smoothed(sample: str) -> np.ndarray:
    im, _ = a.im_map(*a.stokes_of(sample), a.top_prior())
    return a.gblur(im, SIG)


def main(train: str, val: str, dest: str) -> None:
    good = [n for n in sorted(os.listdir(f"{train}/samples"))
            if (m := a.sample_meta(train, n))["split"] == "train" and m["label"] == 0][:300]
    names = [n for n in sorted(os.listdir(f"{val}/samples")) if a.sample_meta(val, n)["split"] == "val"]
    region = a.top_prior() > 0.5
    with ProcessPoolExecutor(2) as ex:
        stack = np.stack(list(ex.map(smoothed, [f"{train}/samples/{n}" for n in good], chunksize=8)))
        med = np.median(stack, 0)
        mad = 1.4826 * np.median(np.abs(stack - med), 0)
        mad = np.maximum(mad, np.quantile(mad[region], 0.05))
        rows = []
        for n, z in zip(names, ex.map(smoothed, [f"{val}/samples/{n}" for n in names], chunksize=8), strict=True):
            u = np.abs((z - med) / mad)[region]
            rows.append({**a.sample_meta(val, n), "sP": float(u.max()), "sP99": float(np.quantile(u, 0.999))})
    json.dump(rows, open(dest, "w"))


if __name__ == "__main__":
    main(*sys.argv[1:4])
