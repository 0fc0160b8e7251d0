"""The good part of seed 1157 that the lens blur (0.7 px before the mosaic, data/so-blur-1157) raises most under the
shipped file's window: its registered features sharp and blurred, and both window maps. Writes blur-part.png and
prints the frames' noise levels. Usage: python blur_part.py OUT.png"""
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
import torch

from model.draem.checkpoint import load_checkpoint
from station.evaluation import model_split

m = "model/weights/default"
ck = load_checkpoint(m)
vm = ck.detector.variation
sharp = model_split(ck, m, "data/line-panel-heldout-1157", "test", good_only=True)
blur = model_split(ck, m, "data/so-blur-1157", "test", good_only=True)
with torch.no_grad():
    a, b = vm.zmaps(sharp.priors), vm.zmaps(blur.priors)
print(f"good parts {len(a.scores)}; noise level median sharp {a.noise_level.median():.2f}, "
      f"blurred {b.noise_level.median():.2f}; window score above 5: sharp {(a.scores > 5).sum()}, "
      f"blurred {(b.scores > 5).sum()}")
j = int((b.scores - a.scores).argmax())
za = vm.clustered(*vm._judged_residual(sharp.priors[j].numpy())[:2])
zb = vm.clustered(*vm._judged_residual(blur.priors[j].numpy())[:2])
y, x = np.unravel_index(int(b.maps[j].argmax()), b.maps[j].shape)
print(f"part {j}: window score sharp {a.scores[j]:.2f}, blurred {b.scores[j]:.2f}, at row {y} column {x}; z there "
      f"sharp {np.round(za[:, y, x], 2)}, blurred {np.round(zb[:, y, x], 2)} (intensity, DoLP, S1/S0, S2/S0)")
fig, ax = plt.subplots(2, 3, figsize=(13, 5))
for r, (name, z, o, pr) in enumerate((("sharp", za, a, sharp), ("blurred 0.7 px", zb, b, blur))):
    ax[r, 0].imshow(pr.priors[j, 0].numpy(), cmap="gray")
    ax[r, 0].set_title(f"{name}: intensity prior")
    ax[r, 1].imshow(z[0], cmap="coolwarm", vmin=-8, vmax=8)
    ax[r, 1].set_title("signed z, intensity")
    ax[r, 2].imshow(o.maps[j].numpy(), cmap="magma", vmin=0, vmax=10)
    ax[r, 2].set_title(f"window map (score {o.scores[j]:.2f})")
    for c in range(3):
        ax[r, c].plot([x], [y], "c+", ms=14)
        ax[r, c].axis("off")
fig.tight_layout()
fig.savefig(sys.argv[1], dpi=80)
