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
for t in ("all", "chip", "dent", "missing_stud", "scratch", "stain"):
    cells = []
    for sep in ("1", "0"):
        d = np.array([float(r["score"]) for r in rows if r["label"] == "1" and r["separable"] == sep
                      and t in ("all", r["defect_type"])])
        cells += [str(len(d)), f"{auroc(np.r_[np.zeros(len(good)), np.ones(len(d))], np.r_[good, d]):.3f}"
                  if len(d) else ""]
    print(f"| {t} | " + " | ".join(cells) + " |")
