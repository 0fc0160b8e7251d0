"""Where the good validation parts' highest place lies (the argmax of the variation map), and a figure of the six
highest-scoring good parts' registered I (1 + DoLP) and maps. Usage: PYTHONPATH=. python where.py MAPS.npz OUT.png
(MAPS from argmax.py)"""

import sys

import matplotlib
import numpy as np
from common import load_val

matplotlib.use("Agg")
import matplotlib.pyplot as plt

d = np.load(sys.argv[1])
maps, lab, sc = d["maps"].astype(np.float32), d["label"], d["scores"]
vm, x, _, _, _ = load_val()
W = maps.shape[2]
g = np.flatnonzero(lab == 0)
order = g[np.argsort(-sc[g])]
print("good scores: median {:.3f} p95 {:.3f} p99 {:.3f} max {:.3f}".format(*np.percentile(sc[g], [50, 95, 99, 100])))
fig, ax = plt.subplots(2, 6, figsize=(22, 5))
for j, i in enumerate(order[:12]):
    y, xx = divmod(int(maps[i].argmax()), W)
    peak = vm.register(x[i].numpy(), x[i, :1].numpy())[-1]  # registered I (1 + DoLP), in full scale
    near = peak[max(0, y - 5):y + 6, max(0, xx - 5):xx + 6].max()
    print(f"part {d['index'][i]}: score {sc[i]:.2f}, highest place ({y}, {xx}), peak there {peak[y, xx]:.2f}, "
          f"within 5 px {near:.2f}")
    if j < 6:
        ax[0, j].imshow(peak, cmap="gray", vmin=0, vmax=1)
        ax[0, j].set_title(f"part {d['index'][i]}, score {sc[i]:.1f}")
        ax[1, j].imshow(maps[i], cmap="inferno", vmin=0, vmax=8)
for a in ax.ravel():
    a.axis("off")
fig.savefig(sys.argv[2], dpi=70, bbox_inches="tight")
