"""Rule 69's two files at the same operating point (stop 96, a reading after the rule, not a decision).

    python matched.py > matched.txt

Rule 69 compared E63 and L63 each at its own threshold: E63's the 1 % bound of the line's validation parts (3 of
370 above), L63's its F1-max point (1 of 370 above), stricter than the bound. Here each file's threshold is put on
seed 1190's own good parts at the same count k (the k-th highest good score passes, k above it rejected), so the
two are compared at the same share of good parts rejected: caught, and L63 minus E63 with a bootstrap SE over parts
(2000 resamples, seed 0; k scaled to each resample's good parts). Reads the committed `station eval` reports in
rule/.
"""
import csv
from pathlib import Path

import numpy as np

HERE = Path(__file__).parent
SETS = {"S": "line-panel-heldout-1190", "G": "om-ggx-1190", "R": "om-rough-1190"}


def read(model: str, name: str) -> tuple[np.ndarray, np.ndarray]:
    rows = sorted(csv.DictReader(open(HERE / "rule" / f"eval-{model}-{name}" / "scores.csv")),
                  key=lambda r: int(r["index"]))
    return np.array([int(r["label"]) for r in rows]), np.array([float(r["score"]) for r in rows])


def caught_at(label: np.ndarray, score: np.ndarray, share: float) -> float:
    good = np.sort(score[label == 0])[::-1]
    k = min(round(share * good.size), good.size - 1)
    return float((score[label == 1] > good[k]).mean())


def main() -> None:
    rng = np.random.default_rng(0)
    print("caught at the same count k of seed 1190's good parts rejected, E63 / L63, L63 - E63 (SE)")
    for key, name in SETS.items():
        y, e = read("E63", name)
        y2, l63 = read("L63", name)
        assert (y == y2).all()
        n_good = int((y == 0).sum())
        cells = []
        for k in (1, 2, 3, 5):
            share = k / n_good
            a, b = caught_at(y, e, share), caught_at(y, l63, share)
            boot = []
            for _ in range(2000):
                i = rng.integers(0, y.size, y.size)
                boot.append(caught_at(y[i], l63[i], share) - caught_at(y[i], e[i], share))
            cells.append(f"k={k}: {100 * a:.1f} / {100 * b:.1f}, {100 * (b - a):+.1f} ({100 * np.std(boot):.1f})")
        print(f"{key} ({n_good} good): " + "; ".join(cells))


if __name__ == "__main__":
    main()
