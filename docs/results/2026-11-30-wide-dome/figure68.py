"""Check 68's figure: probe frames (``probe.py``) side by side, S0 cropped to the part.

Usage (repository root): python docs/results/2026-11-30-wide-dome/figure68.py OUT.png PROBE_DIR TAG:INDEX ...
"""

from __future__ import annotations

import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np


def main() -> None:
    out, folder, pairs = sys.argv[1], Path(sys.argv[2]), [a.split(":") for a in sys.argv[3:]]
    fig, axs = plt.subplots((len(pairs) + 1) // 2, 2, figsize=(12, 1.9 * ((len(pairs) + 1) // 2)), squeeze=False)
    for a, (tag, i) in zip(axs.flat, pairs, strict=False):
        d = np.load(folder / f"{tag}-{i}.npz")
        s0, part = d["s0"], d["mask"] > 0
        ys, xs = np.nonzero(part)
        crop = s0[ys.min() - 12:ys.max() + 12, xs.min() - 8:xs.max() + 8]
        a.imshow(crop, cmap="gray", vmin=0, vmax=float(np.percentile(s0[part], 99.5)))
        a.set_title(f"{tag}: validation sample {i}", fontsize=8)
    for a in axs.flat:
        a.axis("off")
    fig.tight_layout()
    fig.savefig(out, dpi=80)


if __name__ == "__main__":
    main()
