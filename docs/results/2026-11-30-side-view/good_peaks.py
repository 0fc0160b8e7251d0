"""Check 67, after its reading: where the side camera's good validation parts score highest (S's variation map: the
place that sets each part's score), drawn over the variation model's reference, with the rows of the highest 5 %
printed. Validation only.

Usage (repository root): python docs/results/2026-11-30-side-view/good_peaks.py MODEL DATA OUT.png
"""

from __future__ import annotations

import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
import torch

from model.draem.checkpoint import load_checkpoint
from station.evaluation import model_split


def main() -> None:
    model, data, out = sys.argv[1:4]
    ck = load_checkpoint(model)
    vm = ck.detector.variation
    split = model_split(ck, model, data, "val")
    good = np.flatnonzero(np.asarray(split.label) == 0)
    peaks, scores = [], []
    for k in range(0, len(good), 16):
        x = split.priors[good[k:k + 16]]
        o = vm.zmaps(torch.as_tensor(x))
        for m, s in zip(o.maps.numpy(), o.scores.numpy(), strict=True):
            peaks.append(np.unravel_index(int(m.argmax()), m.shape))
            scores.append(float(s))
    peaks, scores = np.array(peaks), np.array(scores)
    top = scores >= np.percentile(scores, 95)
    ref = vm.reference.numpy()
    fig, ax = plt.subplots(figsize=(8, 4.5))
    ax.imshow(ref, cmap="gray")
    ax.contour(vm.region.numpy(), [0.5], colors="c", linewidths=0.6)
    ax.scatter(peaks[~top, 1], peaks[~top, 0], s=6, c="y", label="good part's highest place")
    ax.scatter(peaks[top, 1], peaks[top, 0], s=18, c="r", label="the highest 5 % of good parts")
    ax.legend(fontsize=7, loc="lower right")
    ax.set_title(f"{model} on {data}: {len(good)} good validation parts", fontsize=8)
    ax.axis("off")
    fig.tight_layout()
    fig.savefig(out, dpi=100)
    rows = peaks[top, 0]
    print(f"{len(good)} good parts; the top 5 % ({int(top.sum())}) peak at rows {sorted(rows.tolist())} of "
          f"{ref.shape[0]}; region rows {np.flatnonzero(vm.region.numpy().any(1))[[0, -1]].tolist()}")


if __name__ == "__main__":
    main()
