"""Rule 25, step 1: each defect's contrast in the rendered light, on the same parts under two lines.

For every defective sample of each set: the defect's mean S0 (the rendered ground-truth Stokes, before the sensor)
against the mean of a band up to 5 px around it on the part, ``|ratio - 1|`` (rule 24's measure); the same for DoLP
(absolute change); the face it lies on (``faces.TOP_FACE_Z``); and the share of the part's mosaic pixels at the
sensor's full scale. Writes contrast.json and prints a table.
Usage: python contrast.py data/bf-check-D data/bf-check-B [data/bf-check-F]
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import cv2
import numpy as np
from faces import TOP_FACE_Z  # same folder


def dolp(s0: np.ndarray, s1: np.ndarray, s2: np.ndarray) -> np.ndarray:
    return np.hypot(s1, s2) / np.maximum(s0, 1e-6)


def measure(root: Path) -> list[dict]:
    full = 2 ** json.loads((root / "manifest.json").read_text())["bit_depth"] - 1
    rows = []
    for d in sorted((root / "samples").iterdir()):
        p = json.loads((d / "params.json").read_text())
        if not p.get("defect"):
            continue
        g = np.load(d / "gt.npz")
        m, o = g["defect_mask"] > 0, g["object_mask"] > 0
        if m.sum() < 4:
            continue
        ring = cv2.dilate(m.astype(np.uint8), np.ones((11, 11), np.uint8)).astype(bool) & o & ~m
        s0, s1, s2 = g["s0"], g["s1"], g["s2"]
        raw = cv2.imread(str(d / "raw.png"), cv2.IMREAD_UNCHANGED)
        dl = dolp(s0, s1, s2)
        rows.append({"index": p["index"], "type": p["defect"]["type"],
                     "contrast": float(abs(s0[m].mean() / max(s0[ring].mean(), 1e-9) - 1)),
                     "dolp_change": float(abs(dl[m].mean() - dl[ring].mean())),
                     "normal_z": float(np.median(g["normal"][m][:, 2])),
                     "clipped": float(np.mean(raw[o] >= full))})
    return rows


def main() -> None:
    out = {}
    for root in map(Path, sys.argv[1:]):
        out[root.name] = measure(root)
    Path(__file__).with_name("contrast.json").write_text(json.dumps(out, indent=1))
    names = list(out)
    print("| set | type | face | n | median contrast | median DoLP change | clipped on part: median | 90th pct |")
    print("|---|---|---|---|---|---|---|---|")
    for name in names:
        rows = out[name]
        clipped = np.percentile([r["clipped"] for r in rows], [50, 90])
        for t in sorted({r["type"] for r in rows}):
            for face, sel in (("top", lambda r: r["normal_z"] < TOP_FACE_Z),
                              ("front", lambda r: r["normal_z"] >= TOP_FACE_Z)):
                rs = [r for r in rows if r["type"] == t and sel(r)]
                if rs:
                    print(f"| {name} | {t} | {face} | {len(rs)} | {np.median([r['contrast'] for r in rs]):.3f} | "
                          f"{np.median([r['dolp_change'] for r in rs]):.3f} | {clipped[0]:.4f} | {clipped[1]:.4f} |")


if __name__ == "__main__":
    main()
