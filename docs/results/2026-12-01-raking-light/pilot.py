"""plan.md's pilot: the same parts under the line's light (LINE) and the raking lamp (K), from the renderer's Stokes
(gt.npz, noiseless up to render noise). Prints, per part, the share of the part's pixels whose raw reading clips
(raw.png at code 4095) and, per defect, its contrast in S0: |mean over the defect / mean over a band up to 5 px
around it on the part - 1| (the 2026-11-27 dark-field page's measure), under each light; saves a figure of crops.

Usage: python pilot.py LINE_DATA K_DATA OUT.png"""
import json
import sys
from pathlib import Path

import cv2
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np


def contrast(s0: np.ndarray, defect: np.ndarray, part: np.ndarray) -> float:
    band = cv2.dilate(defect.astype(np.uint8), np.ones((11, 11), np.uint8)).astype(bool) & part & ~defect
    if not band.any() or not defect.any():
        return float("nan")
    return abs(float(s0[defect].mean()) / max(float(s0[band].mean()), 1e-6) - 1)


def main() -> None:
    line, k, out = Path(sys.argv[1]), Path(sys.argv[2]), sys.argv[3]
    rows, crops = [], []
    for d in sorted((k / "samples").iterdir()):
        p = json.loads((d / "params.json").read_text())
        gk, gl = np.load(d / "gt.npz"), np.load(line / "samples" / d.name / "gt.npz")
        raw = cv2.imread(str(d / "raw.png"), cv2.IMREAD_UNCHANGED)
        part = gk["object_mask"]
        clip = float((raw >= 4095)[part].mean())  # the 12-bit mosaic's full scale, same pixel grid as the mask
        dk = p.get("defect") or {}
        row = {"index": p["index"], "type": dk.get("type", "good"), "clip_part": round(clip, 4),
               "face": "front" if dk.get("normal", [0, 0, 1])[1] < -0.5 else "top" if dk else ""}
        if dk and gk["defect_mask"].any():
            m = gk["defect_mask"]
            row.update(px=int(m.sum()), c_line=round(contrast(gl["s0"], gl["defect_mask"], gl["object_mask"]), 3),
                       c_k=round(contrast(gk["s0"], m, part), 3))
            if len(crops) < 8:
                ys, xs = np.nonzero(m)
                cy, cx = int(ys.mean()), int(xs.mean())
                sl = (slice(max(cy - 40, 0), cy + 40), slice(max(cx - 40, 0), cx + 40))
                crops.append((row, gl["s0"][sl], gk["s0"][sl], m[sl]))
        rows.append(row)
        print(row, flush=True)
    defects = [r for r in rows if "c_k" in r]
    for kind in ("blister", "debris"):
        for face in ("top", "front"):
            rs = [r for r in defects if r["type"] == kind and r["face"] == face]
            if rs:
                above = sum(r["c_k"] > r["c_line"] for r in rs)
                print(f"{kind} {face}: n {len(rs)}, median contrast line {np.median([r['c_line'] for r in rs]):.3f}, "
                      f"K {np.median([r['c_k'] for r in rs]):.3f}; K above line {above}")
    print(f"clipped share of the part's pixels under K: median {np.median([r['clip_part'] for r in rows]):.4f}, "
          f"max {max(r['clip_part'] for r in rows):.4f}")
    fig, ax = plt.subplots(2, len(crops), figsize=(2.2 * len(crops), 4.6), squeeze=False)
    for j, (r, a, b, m) in enumerate(crops):
        for i, (img, name) in enumerate(((a, "line"), (b, "raking"))):
            ax[i, j].imshow(img, cmap="gray", vmin=0, vmax=np.percentile(img, 99.5))
            ax[i, j].contour(m, levels=[0.5], colors="r", linewidths=0.6)
            ax[i, j].set_xticks([])
            ax[i, j].set_yticks([])
            ax[i, j].set_title(f"{name} {r['type']} {r['face']}\n{r['px']} px, c {r['c_line' if i == 0 else 'c_k']}",
                               fontsize=7)
    fig.tight_layout()
    fig.savefig(out, dpi=80)


if __name__ == "__main__":
    main()
