"""Image AUROC of the defects the optics show, from the shipped file's report
(docs/results/2026-12-06-visible-auroc.md).

Reads ``model/weights/default-eval/scores.csv`` (``station eval`` on held-out seed 1194: each part's decision score,
label, type and whether the localised oracle separates it, ``separable``) and prints, per type, the image AUROC of the
separable defects and of the others against all good parts: what ``station eval``'s ``image_auroc_separable`` column
(since 2026-12-06) says of that report. Run from the repository's root."""

import csv

import numpy as np

from model.draem.metrics import auroc

rows = list(csv.DictReader(open("model/weights/default-eval/scores.csv")))
good = np.array([float(r["score"]) for r in rows if r["label"] == "0"])
print(f"{len(good)} good parts\n\n| type | shown (separable): defects | image AUROC | not shown: defects "
      "| image AUROC |\n|---|---|---|---|---|")
bars = {}
for t in ("all", "chip", "dent", "missing_stud", "scratch", "stain"):
    cells = []
    for sep in ("1", "0"):
        d = np.array([float(r["score"]) for r in rows if r["label"] == "1" and r["separable"] == sep
                      and t in ("all", r["defect_type"])])
        cells += [str(len(d)), f"{auroc(np.r_[np.zeros(len(good)), np.ones(len(d))], np.r_[good, d]):.3f}"
                  if len(d) else ""]
    print(f"| {t} | " + " | ".join(cells) + " |")
    bars[t] = [float(c) if c else float("nan") for c in cells[1::2]]

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

fig, ax = plt.subplots(figsize=(6.4, 3.2))
x = np.arange(len(bars))
for k, (label, off) in enumerate((("shown at their own pixels (told where)", -0.2), ("not shown", 0.2))):
    ax.bar(x + off, [v[k] for v in bars.values()], 0.4, label=label)
ax.axhline(0.95, color="grey", ls=":", lw=1)
ax.text(len(bars) - 0.5, 0.955, "issue 19: 0.95 per type", fontsize=7, ha="right")
ax.set_xticks(x, [t.replace("_", " ") for t in bars], fontsize=8)
ax.set(ylim=(0.3, 1.02), ylabel="image AUROC against all good parts",
       title="the shipped file on seed 1194: defects the optics show, and the others")
ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.12), ncol=2)
fig.savefig("docs/results/2026-12-06-visible-auroc.png", dpi=110, bbox_inches="tight")
