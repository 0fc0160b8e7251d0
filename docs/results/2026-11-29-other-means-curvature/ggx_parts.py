"""The good parts of seed 1163 that the shipped file rejects rendered with GGX microfacets (data/om-ggx-1163) but
not as built (data/line-panel-heldout-1163): both renders' intensity prior, signed z of intensity and window map, and
what the z is there per channel. Writes ggx-parts.png. Usage: python ggx_parts.py RUNS_DIR OUT.png"""
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
import torch

from model.draem.checkpoint import load_checkpoint
from station.eval_compare import read_scores
from station.evaluation import model_split

runs, out = sys.argv[1:3]
m = "model/weights/default"
ck = load_checkpoint(m)
vm = ck.detector.variation
T = float(ck.threshold)


def good_over(name):
    return {i for i, (label, _, score) in read_scores(f"{runs}/eval-{name}").items() if label == 0 and score > T}


parts = sorted(good_over("K3-G") - good_over("K3-S"))
S = model_split(ck, m, "data/line-panel-heldout-1163", "test")
G = model_split(ck, m, "data/om-ggx-1163", "test")
with torch.no_grad():
    a, b = vm.zmaps(S.priors[parts]), vm.zmaps(G.priors[parts])
fig, ax = plt.subplots(len(parts), 4, figsize=(16, 2.4 * len(parts)), squeeze=False)
for k, i in enumerate(parts):
    y, x = np.unravel_index(int(b.maps[k].argmax()), b.maps[k].shape)
    zs = vm.clustered(*vm._judged_residual(S.priors[i].numpy())[:2])
    zg = vm.clustered(*vm._judged_residual(G.priors[i].numpy())[:2])
    print(f"part {i}: window as built {a.scores[k]:.2f}, GGX {b.scores[k]:.2f} at row {y} column {x}; z there as built "
          f"{np.round(zs[:, y, x], 1)}, GGX {np.round(zg[:, y, x], 1)} (intensity, DoLP, S1/S0, S2/S0); highlight "
          f"share {a.highlight_fraction[k]:.3f} / {b.highlight_fraction[k]:.3f}")
    for c, (img, title, kw) in enumerate((
            (S.priors[i, 0].numpy(), f"part {i} as built: intensity", {"cmap": "gray", "vmin": 0, "vmax": 1}),
            (G.priors[i, 0].numpy(), "GGX: intensity", {"cmap": "gray", "vmin": 0, "vmax": 1}),
            (zg[0], "GGX: signed z, intensity", {"cmap": "coolwarm", "vmin": -8, "vmax": 8}),
            (b.maps[k].numpy(), f"GGX: window map ({b.scores[k]:.1f}; as built {a.scores[k]:.1f})",
             {"cmap": "magma", "vmin": 0, "vmax": 10}))):
        ax[k, c].imshow(img, **kw)
        ax[k, c].plot([x], [y], "c+", ms=14)
        ax[k, c].set_title(title, fontsize=9)
        ax[k, c].axis("off")
fig.tight_layout()
fig.savefig(out, dpi=70)
