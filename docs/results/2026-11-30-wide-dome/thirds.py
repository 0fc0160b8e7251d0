"""Check 68: how many good parts of a side-camera set show part of the body's front face dark: the median S0 of the
face's left, middle and right thirds (by column; ground-truth part index and camera-frame normals z > 0.9), and the
share of good parts whose darkest third reads under 0.6 of the brightest (the test's measure,
tests/sim/test_sim_view.py).

Usage (repository root): python docs/results/2026-11-30-wide-dome/thirds.py DATA [DATA ...]
"""

from __future__ import annotations

import sys

import numpy as np

from model.priors.demosaic import mosaic_to_stokes
from model.priors.mosaic import normalize_mosaic
from sim.dataset import open_dataset

BODY = 1
"""The body's part index (0 is the background)."""


def thirds(s0: np.ndarray, part_index: np.ndarray, normal: np.ndarray) -> list[float]:
    face = (part_index == BODY) & (normal[..., 2] > 0.9)
    cols = np.array_split(np.flatnonzero(face.any(0)), 3)
    return [float(np.median(s0[:, c][face[:, c]])) for c in cols]


def main() -> None:
    print("| set | good parts | darkest third under 0.6 of the brightest | under 0.8 | darkest / brightest, 1st pct |")
    print("|---|---|---|---|---|")
    for root in sys.argv[1:]:
        ds = open_dataset(root)
        ratios = []
        for i in ds.indices():
            s = ds.load(i)
            if s.label or s.part_index is None or not (s.part_index == BODY).any():
                continue
            s0, _, _ = mosaic_to_stokes(normalize_mosaic(s.raw).data)
            lv = thirds(s0, s.part_index, s.normal)
            ratios.append(min(lv) / max(lv))
        r = np.array(ratios)
        print(f"| {root} | {r.size} | {int((r < 0.6).sum())} ({(r < 0.6).mean():.1%}) | {int((r < 0.8).sum())} "
              f"({(r < 0.8).mean():.1%}) | {np.percentile(r, 1):.2f} |")


if __name__ == "__main__":
    main()
