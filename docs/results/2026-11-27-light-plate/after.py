"""Rule 33, read after its outcome: where the light plate's good parts score high. The variation model Q's z map
(``VariationModel.zmaps``) of the held-out set's good parts with the highest scores and of two typical ones, beside
their intensity prior, with each part's score, noise level and highlight share; and the good parts' score
percentiles under P and Q (from the committed reports' scores.csv).
Usage: python after.py runs/lp/Q data/lp-heldout OUT.png (run from the repository root; prints markdown);
python after.py runs/lp/Q data/lp-spp64 --rescore: Q's scores of the parts in a set of a few parts ([spp64.sh]
renders some again at 64 samples per pixel)."""

from __future__ import annotations

import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

from model.draem.checkpoint import load_checkpoint
from station.datasets import load_split

D = "docs/results/2026-11-27-light-plate"


def good_scores(line: str) -> dict[int, float]:
    rows = csv.DictReader(open(f"{D}/eval-{line}/scores.csv"))
    return {int(r["index"]): float(r["variation"]) for r in rows if r["label"] == "0"}


def load(model: str, data: str):
    ck = load_checkpoint(model)
    cfg = ck.detector.config
    return ck.detector.variation, load_split(data, "test", cfg.priors, cfg.input_shape, roi=cfg.roi,
                                             frame_aspect=cfg.frame_aspect, progress=False)


def rescore(model: str, data: str) -> None:
    v, sp = load(model, data)
    z = v.zmaps(sp.priors)
    print("| part | Q score | noise level |\n|---|---|---|")
    for i, s, n in zip(sp.index, z.scores, z.noise_level, strict=True):
        print(f"| {i} | {float(s):.1f} | {float(n):.2f} |")


def main() -> None:
    if sys.argv[3] == "--rescore":
        return rescore(*sys.argv[1:3])
    model, data, out = sys.argv[1:4]
    p, q = good_scores("P"), good_scores("Q")
    print("| good parts' variation score | 50th | 90th | 95th | 99th |\n|---|---|---|---|---|")
    for name, s in (("P: shipped line", p), ("Q: light plate", q)):
        print(f"| {name} | " + " | ".join(f"{v:.1f}" for v in np.percentile(list(s.values()), [50, 90, 95, 99])) + " |")
    ranked = sorted(q, key=lambda i: -q[i])
    pick = ranked[:6] + ranked[len(ranked) // 2:len(ranked) // 2 + 2]
    v, sp = load(model, data)
    rows = [sp.index.index(i) for i in pick]
    z = v.zmaps(sp.priors[rows])
    print("\n| part | Q score | P score | noise level | highlight share |\n|---|---|---|---|---|")
    fig, ax = plt.subplots(len(rows), 2, figsize=(7, 1.6 * len(rows)))
    for k, i in enumerate(pick):
        level, hidden = float(z.noise_level[k]), float(z.highlight_fraction[k])
        print(f"| {i} | {q[i]:.1f} | {p[i]:.1f} | {level:.2f} | {hidden:.2f} |")
        ax[k, 0].imshow(sp.priors[rows[k], 0].numpy(), cmap="gray", vmax=1.0)
        ax[k, 1].imshow(z.maps[k].numpy(), vmin=0, vmax=10)
        ax[k, 0].set_title(f"good part {i}: intensity", fontsize=7)
        ax[k, 1].set_title(f"Q's map (0 to 10): score {q[i]:.1f}, P's {p[i]:.1f}", fontsize=7)
        for a in ax[k]:
            a.set_axis_off()
    fig.tight_layout()
    fig.savefig(out, dpi=70)


if __name__ == "__main__":
    main()
