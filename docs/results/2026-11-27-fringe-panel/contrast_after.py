"""Read after rule 32's outcome, to understand it: each defect's contrast in the rendered light (rule 25's
``contrast.measure``: mean S0 on the defect against a band up to 5 px around it) on the same held-out parts under
the shipped line and the fringe panel, paired per defect, by type and face. Writes contrast.json here.
Usage: python contrast_after.py data/line-panel-heldout-1132 data/fr-heldout
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import cv2
import numpy as np
from scipy.stats import spearmanr

sys.path.insert(0, str(Path(__file__).parents[1] / "2026-11-27-bright-field"))
from contrast import measure  # rule 25's, unchanged
from faces import TOP_FACE_Z


def main() -> None:
    roots = [Path(a) for a in sys.argv[1:3]]
    p, r = ({row["index"]: row for row in measure(Path(a))} for a in roots)
    pairs = [(p[i], r[i]) for i in sorted(set(p) & set(r))]
    Path(__file__).with_name("contrast.json").write_text(json.dumps({"P": list(p.values()), "R": list(r.values())}))
    print("| type | face | n | median contrast P | R | median ratio R / P | lower under R |")
    print("|---|---|---|---|---|---|---|")
    for t in sorted({a["type"] for a, _ in pairs}):
        for face, top in (("top", True), ("front", False)):
            rs = [(a, b) for a, b in pairs if a["type"] == t and (a["normal_z"] < TOP_FACE_Z) == top]
            if rs:
                cp, cr = (np.array([x[k]["contrast"] for x in rs]) for k in (0, 1))
                print(f"| {t} | {face} | {len(rs)} | {np.median(cp):.3f} | {np.median(cr):.3f} | "
                      f"{np.median(cr / np.maximum(cp, 1e-9)):.2f} | {int((cr < cp).sum())} of {len(rs)} |")

    scratches = [a["index"] for a, _ in pairs if a["type"] == "scratch" and a["normal_z"] < TOP_FACE_Z]
    light = [band_s0(roots[1], i) / band_s0(roots[0], i) for i in scratches]
    kept = [r[i]["contrast"] / max(p[i]["contrast"], 1e-9) for i in scratches]
    rho = spearmanr(light, kept)
    print(f"\ntop-face scratches: the band's brightness R / P, median {np.median(light):.2f} "
          f"(range {min(light):.2f}-{max(light):.2f}); Spearman rho against the contrast ratio R / P: "
          f"{rho.statistic:.2f} (p = {rho.pvalue:.2g}, n = {len(light)})")


def band_s0(root: Path, index: int) -> float:
    """Mean rendered S0 of the band up to 5 px around the defect on the part (``contrast.measure``'s band)."""
    g = np.load(root / "samples" / f"{index:06d}" / "gt.npz")
    m, o = g["defect_mask"] > 0, g["object_mask"] > 0
    band = cv2.dilate(m.astype(np.uint8), np.ones((11, 11), np.uint8)).astype(bool) & o & ~m
    return float(g["s0"][band].mean())


if __name__ == "__main__":
    main()
