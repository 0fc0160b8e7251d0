"""The page's figure: under the raking lamp (K), the three good parts of the new kinds' validation twins that K
scores highest, and three blisters K separates at their own pixels but misses at its threshold; each K's intensity
prior, the signed z of intensity and the window map, the map's highest place marked.

Usage: python figures.py RUNS_DIR OUT.png (RUNS_DIR: run.sh's runs/c77)"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
import torch

from model.draem.checkpoint import load_checkpoint
from station.evaluation import model_split

runs, out = sys.argv[1:3]
m = f"{runs}/K"
ck = load_checkpoint(m)
vm = ck.detector.variation
T = float(ck.threshold)
rows = list(csv.DictReader(open(f"{runs}/eval-K-new/scores.csv")))
good = sorted((r for r in rows if r["label"] == "0"), key=lambda r: -float(r["score"]))[:3]
missed = [r for r in rows if r["defect_type"] == "blister" and r["separable"] == "1" and float(r["score"]) <= T]
missed = sorted(missed, key=lambda r: -float(r["score"]))[:3]
picks = [("good", r) for r in good] + [("blister, missed", r) for r in missed]
split = model_split(ck, m, "data/raking-new-kinds-val-1180", "val")
pos = {int(i): k for k, i in enumerate(split.index)}
fig, ax = plt.subplots(len(picks), 3, figsize=(12, 2.3 * len(picks)), squeeze=False)
for k, (what, r) in enumerate(picks):
    x = split.priors[pos[int(r["index"])]]
    with torch.no_grad():
        o = vm.zmaps(x[None])
    y, c = np.unravel_index(int(o.maps[0].argmax()), o.maps[0].shape)
    z = vm.clustered(*vm._judged_residual(x.numpy())[:2])
    print(f"{what} {r['index']} ({r['face']}): score {float(r['score']):.3f} (threshold {T:.3f}), window's highest "
          f"place row {y} column {c}")
    for j, (img, title, kw) in enumerate((
            (x[0].numpy(), f"{what}, part {r['index']} {r['face']}: intensity", {"cmap": "gray", "vmin": 0, "vmax": 1}),
            (z[0], "signed z, intensity", {"cmap": "coolwarm", "vmin": -8, "vmax": 8}),
            (o.maps[0].numpy(), f"window map (score {float(r['score']):.2f})", {"cmap": "magma", "vmin": 0,
                                                                               "vmax": 10}))):
        ax[k, j].imshow(img, **kw)
        ax[k, j].plot([c], [y], "c+", ms=14)
        ax[k, j].set_title(title, fontsize=8)
        ax[k, j].axis("off")
fig.tight_layout()
fig.savefig(out, dpi=70)
