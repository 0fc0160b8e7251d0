"""Twin renders of the validation set's first 150 parts with and without the stray lamp (sim/presets/variation.toml's
spot; docs/results/2026-11-30-report-1167/no-stray.toml): how much each candidate feature changes, against the
change between twins without a lamp (sensor and render noise only), both smoothed 2 px over the part, median taken
out; and a picture of the four strongest lamps' changes.

    python twins.py data/line-pv-val data/line-pv-val-nostray twins.png > twins.txt
"""
import json
import os
import sys

import cv2
import matplotlib
import numpy as np
from PIL import Image

from model.priors.demosaic import mosaic_to_stokes
from model.priors.mosaic import normalize_mosaic

matplotlib.use("Agg")
import matplotlib.pyplot as plt

BAND = (slice(120, 360), slice(80, 560))


def feats(path: str) -> tuple[np.ndarray, dict[str, np.ndarray]]:
    raw = np.array(Image.open(f"{path}/raw.png"))
    s0, s1, s2 = (c[BAND].astype(np.float32) for c in mosaic_to_stokes(normalize_mosaic(raw, 12).data))
    m = np.load(f"{path}/gt.npz")["object_mask"][BAND]
    med, p = np.median(s0[m]), np.hypot(s1, s2)
    return m, {"log S0": np.log(np.maximum(s0, 1e-3)), "log P": np.log(np.maximum(p, 1e-3)),
               "S1/S0": s1 / np.maximum(s0, 1e-3), "S2/S0": s2 / np.maximum(s0, 1e-3),
               "S1/median S0": s1 / med, "S2/median S0": s2 / med, "log(S0-P)": np.log(np.maximum(s0 - p, 1e-3))}


def change(a: str, b: str, key: str) -> tuple[np.ndarray, np.ndarray]:
    (ma, fa), (mb, fb) = feats(a), feats(b)
    return cv2.GaussianBlur((fa[key] - fb[key]).astype(np.float32), (0, 0), 2.0), ma & mb


def main(with_lamp: str, without: str, picture: str) -> None:
    pairs = {"lamp": [], "none": []}
    for n in sorted(os.listdir(f"{without}/samples")):
        pa, pb = (json.load(open(f"{r}/samples/{n}/params.json")) for r in (with_lamp, without))
        if pa["label"] or pa["split"] != "val":
            continue
        assert pa["scene"]["pose"] == pb["scene"]["pose"], n  # twins: the same part, pose and draws
        pairs["lamp" if pa["scene"]["light"]["intensity"] > 0.05 else "none"].append((n, pa["scene"]["light"]))
    rms: dict[str, dict[str, list[float]]] = {k: {} for k in pairs}
    for kind, items in pairs.items():
        for n, _ in items:
            for key in feats(f"{with_lamp}/samples/{n}")[1]:
                d, m = change(f"{with_lamp}/samples/{n}", f"{without}/samples/{n}", key)
                d = d[m] - np.median(d[m])
                rms[kind].setdefault(key, []).append(float(np.sqrt(np.mean(d ** 2))))
    print(f"good twins: {len(pairs['lamp'])} with a lamp above 0.05, {len(pairs['none'])} without (noise only)\n")
    print("| feature | change with a lamp: median (90th pct) | without | ratio (90th pct) |\n|---|---|---|---|")
    for key, v in rms["lamp"].items():
        z = np.median(rms["none"][key])
        print(f"| {key} | {np.median(v):.4f} ({np.percentile(v, 90):.4f}) | {z:.4f} | {np.median(v) / z:.2f} "
              f"({np.percentile(v, 90) / z:.2f}) |")
    strongest = sorted(pairs["lamp"], key=lambda r: -r[1]["intensity"])[:4]
    keys = ["log S0", "log P", "S1/median S0", "S2/median S0"]
    fig, ax = plt.subplots(4, 5, figsize=(20, 9))
    for i, (n, light) in enumerate(strongest):
        ax[i, 0].imshow(feats(f"{with_lamp}/samples/{n}")[1]["log S0"], cmap="gray")
        ax[i, 0].set_title(f"{n}, lamp {light['intensity']:.2f}")
        for j, key in enumerate(keys):
            d, m = change(f"{with_lamp}/samples/{n}", f"{without}/samples/{n}", key)
            v = np.percentile(np.abs(d[m]), 99)
            ax[i, j + 1].imshow(d * m, cmap="coolwarm", vmin=-v, vmax=v)
            ax[i, j + 1].set_title(f"{key} +-{v:.3f}")
    for a in ax.flat:
        a.axis("off")
    fig.tight_layout()
    fig.savefig(picture, dpi=60)


if __name__ == "__main__":
    main(*sys.argv[1:4])
