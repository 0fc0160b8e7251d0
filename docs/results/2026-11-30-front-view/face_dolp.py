"""Check 66: the front and top faces' DoLP from each camera, on seed 1167's good parts: the renderer's noiseless
value (gt.npz) against the frame's (demosaiced from the raw mosaic, smoothed by 2.5 px as figure66.py), and the
faces' intensity. Faces by the ground-truth normal (camera frame, body only, |n_x| < 0.3): the line camera sees the
top face at z ~ 0.56 and the front at ~ 0.83, the second camera the other way round.
Usage (repository root): python docs/results/2026-11-30-front-view/face_dolp.py"""

from __future__ import annotations

import json
from pathlib import Path

import cv2
import numpy as np

from model.priors.api import compute_priors

SETS = {"line camera": ("data/line-panel-heldout-1167", True), "second camera": ("data/fv-heldout-1167", False)}
BODY = 1
"""``part_index`` of the brick's body in gt.npz (studs and plug are 2 and 3)."""


def main() -> None:
    print("| camera | face | DoLP, noiseless (median over parts) | DoLP, frame | intensity, frame |")
    print("|---|---|---|---|---|")
    for name, (data, front_high) in SETS.items():
        rows: dict[str, list[tuple[float, float, float]]] = {"front": [], "top": []}
        for d in sorted(Path(data, "samples").iterdir())[:80]:
            if json.loads((d / "params.json").read_text())["label"]:
                continue
            g = np.load(d / "gt.npz")
            raw = cv2.imread(str(d / "raw.png"), cv2.IMREAD_UNCHANGED)
            p = compute_priors(raw, bit_depth=12, priors=("intensity", "dolp"))
            dolp = cv2.GaussianBlur(p["dolp"], (0, 0), 2.5)
            true = np.hypot(g["s1"], g["s2"]) / np.maximum(g["s0"], 1e-6)
            body = g["object_mask"] & (g["part_index"] == BODY) & (np.abs(g["normal"][..., 0]) < 0.3)
            high = g["normal"][..., 2] > 0.7
            front = body & (high if front_high else ~high)
            for face, m in (("front", front), ("top", body & ~front)):
                m = cv2.erode(m.astype(np.uint8), np.ones((7, 7), np.uint8)).astype(bool)  # away from the edges
                if m.sum() > 50:
                    rows[face].append((np.median(true[m]), np.median(dolp[m]), np.median(p["intensity"][m])))
        for face, r in rows.items():
            a = np.array(r)
            true, frame, level = np.median(a, axis=0)
            print(f"| {name} | {face} | {true:.3f} | {frame:.3f} | {level:.3f} |")


if __name__ == "__main__":
    main()
