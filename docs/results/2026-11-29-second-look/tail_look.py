"""tail.png: six good validation parts the second look raises (validation only), each with its registered log
intensity, its window map and its signed residual per channel (log I and the two Stokes components; the DoLP
channel is not read). Usage: PYTHONPATH=. python tail_look.py (from the repository root)."""

import copy

import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt

from model.draem.checkpoint import load_checkpoint
from station.evaluation import model_split

M = "model/weights/default"
ck = load_checkpoint(M)
vm = copy.deepcopy(ck.detector.variation)
vm.second_look.calibration[0] = np.inf  # window maps without the second look
sp = model_split(ck, M, "data/line-panel-val", "val")
want = [540, 218, 72, 297, 585, 457]
rows = [list(sp.index).index(w) for w in want]
x = sp.priors[rows].float()
o = vm.zmaps(x, signed=True)
fig, ax = plt.subplots(len(rows), 5, figsize=(20, 2.2 * len(rows)))
for r, (i, m, s) in enumerate(zip(want, o.maps.numpy(), o.signed.numpy(), strict=True)):
    xi = x[r].numpy()
    ax[r, 0].imshow(vm.register(xi, vm.features(xi))[0])
    ax[r, 0].set_title(f"{i} logI registered")
    ax[r, 1].imshow(m)
    ax[r, 1].set_title("window map")
    for col, c in ((2, 0), (3, 2), (4, 3)):
        ax[r, col].imshow(s[c], cmap="RdBu", vmin=-8, vmax=8)
        ax[r, col].set_title(f"signed z c{c}")
for a in ax.flat:
    a.axis("off")
plt.tight_layout()
plt.savefig("docs/results/2026-11-29-second-look/tail.png", dpi=60)
