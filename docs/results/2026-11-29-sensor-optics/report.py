"""The screen's table (plan.md): for each re-exposed set, good parts rejected at the shipped threshold, image AUROC
and caught at the 1 % threshold, with paired differences (SE over the parts) against `none`.

    PYTHONPATH=. python report.py runs/s57   (reads eval-so-<kind>/scores.csv)
"""

from __future__ import annotations

import csv
import sys
from pathlib import Path

import numpy as np
from sklearn.metrics import roc_auc_score

KINDS = ("none", "blur", "vignette", "er100", "angles", "prnu", "all")
THRESHOLD, T1 = 0.5965062379837036, 0.9863  # the shipped file's threshold and its 1 % threshold (eval.md)


def read(path: Path) -> tuple[np.ndarray, np.ndarray]:
    rows = list(csv.DictReader(path.open()))
    return np.array([float(r["score"]) for r in rows]), np.array([int(r["label"]) for r in rows])


def main(runs: Path) -> None:
    base, label = read(runs / "eval-so-none" / "scores.csv")
    good = label == 0
    print("| camera | good rejected at the threshold | difference (SE) | image AUROC | caught at 1 % |")
    print("|---|---|---|---|---|")
    for k in KINDS:
        f = runs / f"eval-so-{k}" / "scores.csv"
        if not f.is_file():
            continue
        s, lab = read(f)
        assert np.array_equal(lab, label)
        rej, rej0 = (s[good] > THRESHOLD).astype(float), (base[good] > THRESHOLD).astype(float)
        d = rej - rej0
        se = d.std(ddof=1) / np.sqrt(d.size)
        caught, false = 100 * (s[~good] > T1).mean(), 100 * (s[good] > T1).mean()
        print(f"| {k} | {100 * rej.mean():.1f} % | {100 * d.mean():+.1f} ({100 * se:.1f}) | "
              f"{roc_auc_score(lab, s):.3f} | {caught:.1f} % ({false:.1f} %) |")


if __name__ == "__main__":
    main(Path(sys.argv[1]))
