"""The priors ablation's measure 1 (plan.md): defective parts caught at the same count k of each set's good parts
rejected, pooled over the sets, and each pair's difference with a bootstrap SE over parts.

    python matched.py > matched.txt   (from the repository root: PYTHONPATH=. .venv/bin/python ...)

Reads the committed `station eval` reports eval-{R,RA,RAD}-{seed}/scores.csv beside this file. On each set k good
parts are rejected: the threshold is the (k+1)-th highest good score and a part above it is rejected (plan.md's
"the k-th highest good score is the threshold's place" rejects k - 1 under that rule: its k = 2 is the k = 1 row
here); k is scaled to a resample's good parts. Parts are resampled within each set (2000 draws, seed 0).
"""
import csv
from pathlib import Path

import numpy as np

from model.draem.metrics import auroc

HERE = Path(__file__).parent
MODELS = ("R", "RA", "RAD")
SEEDS = (1191, 1192)
PAIRS = (("RAD", "R"), ("RA", "R"), ("RAD", "RA"))


def read(model: str, seed: int) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """(labels, scores, defect types, faces) of one report, in index order."""
    rows = sorted(csv.DictReader(open(HERE / f"eval-{model}-{seed}" / "scores.csv")), key=lambda r: int(r["index"]))
    return (np.array([int(r["label"]) for r in rows]), np.array([float(r["score"]) for r in rows]),
            np.array([r["defect_type"] for r in rows]), np.array([r["face"] for r in rows]))


def caught(label: np.ndarray, score: np.ndarray, share: float) -> tuple[int, int]:
    """(caught, defective) with k = round(share x good) good parts rejected: the threshold is the (k+1)-th highest
    good score, and a part is rejected when its score is above it (the station's rule)."""
    good = np.sort(score[label == 0])[::-1]
    k = min(round(share * good.size), good.size - 1)
    return int((score[label == 1] > good[k]).sum()), int((label == 1).sum())


def pooled(sets: list[tuple[np.ndarray, np.ndarray]], shares: list[float]) -> float:
    hits = [caught(y, s, f) for (y, s), f in zip(sets, shares, strict=True)]
    return sum(h for h, _ in hits) / sum(n for _, n in hits)


def main() -> None:
    data = {(m, seed): read(m, seed) for m in MODELS for seed in SEEDS}
    labels = {seed: data["RAD", seed][0] for seed in SEEDS}
    for m in MODELS:
        for seed in SEEDS:
            assert (data[m, seed][0] == labels[seed]).all() and (data[m, seed][2] == data["RAD", seed][2]).all()
    n_good = {seed: int((labels[seed] == 0).sum()) for seed in SEEDS}
    print("caught at the same count k of each set's good parts rejected, pooled over seeds "
          + ", ".join(f"{s} ({n_good[s]} good, {labels[s].size - n_good[s]} defective)" for s in SEEDS))
    rng = np.random.default_rng(0)
    for k in (1, 2, 8):
        shares = [k / n_good[s] for s in SEEDS]
        level = {m: pooled([data[m, s][:2] for s in SEEDS], shares) for m in MODELS}
        boot = {p: [] for p in PAIRS}
        for _ in range(2000):
            idx = {s: rng.integers(0, labels[s].size, labels[s].size) for s in SEEDS}
            lv = {m: pooled([(data[m, s][0][idx[s]], data[m, s][1][idx[s]]) for s in SEEDS], shares)
                  for m in MODELS}
            for a, b in PAIRS:
                boot[a, b].append(lv[a] - lv[b])
        print(f"k = {k}: " + ", ".join(f"{m} {100 * level[m]:.1f} %" for m in MODELS) + "; "
              + "; ".join(f"{a} - {b} {100 * (level[a] - level[b]):+.1f} (SE {100 * np.std(boot[a, b]):.1f}, "
                          f"{(level[a] - level[b]) / np.std(boot[a, b]):+.1f} SE)" for a, b in PAIRS))
        for seed in SEEDS:
            y = labels[seed]
            cells = []
            for m in MODELS:
                h, n = caught(y, data[m, seed][1], k / n_good[seed])
                cells.append(f"{m} {h}/{n}")
            print(f"    seed {seed}: " + ", ".join(cells))
    print("image AUROC, both seeds' parts together; pair differences with a paired bootstrap SE over parts")
    y = np.concatenate([labels[s] for s in SEEDS])
    types = np.concatenate([data["RAD", s][2] for s in SEEDS])
    score = {m: np.concatenate([data[m, s][1] for s in SEEDS]) for m in MODELS}
    faces = np.concatenate([data["RAD", s][3] for s in SEEDS])
    by_face = [(f"{t} on the {f} face", (types == t) & (faces == f))
               for t in ("dent", "scratch") for f in ("top", "front")]
    for t, chosen in [("all", y >= 0), *[(t, types == t) for t in sorted(set(types) - {""})], *by_face]:
        if t == by_face[0][0]:
            print("beyond the plan (observed, not tested): by face")
        keep = chosen | (y == 0)
        yt, st = y[keep], {m: score[m][keep] for m in MODELS}
        level = {m: auroc(yt, st[m]) for m in MODELS}
        boot = {p: [] for p in PAIRS}
        for _ in range(2000):
            i = rng.integers(0, yt.size, yt.size)
            lv = {m: auroc(yt[i], st[m][i]) for m in MODELS}
            for a, b in PAIRS:
                boot[a, b].append(lv[a] - lv[b])
        print(f"{t} ({int((yt == 1).sum())}): " + ", ".join(f"{m} {level[m]:.3f}" for m in MODELS) + "; "
              + "; ".join(f"{a} - {b} {level[a] - level[b]:+.3f} (SE {np.std(boot[a, b]):.3f}, "
                          f"{(level[a] - level[b]) / np.std(boot[a, b]):+.1f} SE)" for a, b in PAIRS))


if __name__ == "__main__":
    main()
