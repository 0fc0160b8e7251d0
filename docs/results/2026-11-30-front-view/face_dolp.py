"""Check 66: the front and top faces' DoLP from each camera, on seed 1167's good parts: the renderer's noiseless
value (gt.npz) against the frame's (demosaiced from the raw mosaic and smoothed by ``figure66.frame_maps``), and
the faces' intensity. Faces by the ground-truth normal (camera frame, body only, |n_x| < 0.3): the line camera sees
the top face at z ~ 0.56 and the front at ~ 0.83, the second camera the other way round.
Usage (repository root): python docs/results/2026-11-30-front-view/face_dolp.py"""

from __future__ import annotations

import cv2
import numpy as np
from figure66 import frame_maps

from sim.dataset import Dataset

SETS = {"line camera": ("data/line-panel-heldout-1167", True), "second camera": ("data/fv-heldout-1167", False)}
BODY = 1
"""``part_index`` of the brick's body in gt.npz (studs and plug are 2 and 3)."""


def main() -> None:
    print("| camera | face | DoLP, noiseless (median over parts) | DoLP, frame | intensity, frame |")
    print("|---|---|---|---|---|")
    for name, (data, front_high) in SETS.items():
        rows: dict[str, list[tuple[float, float, float]]] = {"front": [], "top": []}
        ds = Dataset(data)
        for i in ds.indices()[:80]:
            g = ds.load(i)
            if g.label:
                continue
            intensity, dolp = frame_maps(g, ds.manifest["bit_depth"])
            true = np.hypot(g.s1, g.s2) / np.maximum(g.s0, 1e-6)
            body = g.object_mask & (g.part_index == BODY) & (np.abs(g.normal[..., 0]) < 0.3)
            high = g.normal[..., 2] > 0.7
            front = body & (high if front_high else ~high)
            for face, m in (("front", front), ("top", body & ~front)):
                m = cv2.erode(m.astype(np.uint8), np.ones((7, 7), np.uint8)).astype(bool)  # away from the edges
                if m.sum() > 50:
                    rows[face].append((np.median(true[m]), np.median(dolp[m]), np.median(intensity[m])))
        for face, r in rows.items():
            a = np.array(r)
            true, frame, level = np.median(a, axis=0)
            print(f"| {name} | {face} | {true:.3f} | {frame:.3f} | {level:.3f} |")


if __name__ == "__main__":
    main()
