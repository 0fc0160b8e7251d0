"""Two files on the same held-out parts at matched rates of good parts rejected (plan.md): for each file, the
defective parts caught when at most 1 %, 2 % and 5 % of the set's good parts score above its threshold there (the
threshold from the set's good parts, as a line's own would be set), B - A with a bootstrap SE (good and defective
parts resampled apart, 2000 times), and each file at its own validation threshold.

Usage: python curves.py FIRST SECOND SET (checkpoints without suffix; SET's test split; run from the repository's
root with PYTHONPATH=.)."""

import math
import sys

import numpy as np

from model.draem.adapt import image_scores
from model.draem.checkpoint import load_checkpoint
from station.evaluation import model_split

RATES = (0.01, 0.02, 0.05)


def caught_at(good: np.ndarray, bad: np.ndarray, rate: float) -> float:
    """Share of ``bad`` scoring above the threshold that rejects at most floor(rate * len(good)) of ``good``."""
    k = math.floor(rate * len(good))
    threshold = np.sort(good)[::-1][k]  # the (k+1)-th highest good score: parts above it are rejected
    return float((bad > threshold).mean())


def main(first: str, second: str, data: str) -> None:
    scores, own = [], []
    for path in (first, second):
        ck = load_checkpoint(path)
        sp = model_split(ck, path, data, "test")
        s = image_scores(ck.detector, sp.priors.float(), around=None if sp.around is None else sp.around.float())
        lab = sp.label.numpy() == 1
        scores.append((sp.index, lab, np.asarray(s, dtype=float)))
        rej = s > ck.threshold
        own.append((int(rej[~lab].sum()), int((~lab).sum()), int(rej[lab].sum()), int(lab.sum()), ck.threshold))
    assert scores[0][0] == scores[1][0]
    lab = scores[1][1]
    (_, _, a), (_, _, b) = scores
    print(f"== {data}: {int((~lab).sum())} good, {int(lab.sum())} defective parts")
    for path, (rg, ng, rd, nd, thr) in zip((first, second), own, strict=True):
        print(f"{path} at its own threshold {thr:.4f}: {rg} of {ng} good rejected, {rd} of {nd} defective caught "
              f"({100 * rd / nd:.1f} %)")
    matched(a, b, lab)


def matched(a: np.ndarray, b: np.ndarray, lab: np.ndarray, names: tuple[str, str] = ("A", "B")) -> None:
    """Print the table: each of two score arrays' defective parts caught (``lab`` True) at each of ``RATES`` of the
    good parts rejected, the second less the first with a bootstrap SE, and their mean over the rates."""
    first, second = names
    rng = np.random.default_rng(0)
    gi, di = np.flatnonzero(~lab), np.flatnonzero(lab)
    boots = []
    for _ in range(2000):
        g, d = rng.choice(gi, len(gi)), rng.choice(di, len(di))
        boots.append([caught_at(b[g], b[d], r) - caught_at(a[g], a[d], r) for r in RATES])
    boots = np.array(boots)
    diffs = []
    print(f"| good parts rejected at most | {first} caught | {second} caught | {second} - {first} (points) | "
          "bootstrap SE |")
    print("|---|---|---|---|---|")
    for j, r in enumerate(RATES):
        k = math.floor(r * len(gi))
        ca, cb = caught_at(a[gi], a[di], r), caught_at(b[gi], b[di], r)
        diffs.append(cb - ca)
        print(f"| {100 * r:.0f} % ({k} of {len(gi)}) | {100 * ca:.1f} % | {100 * cb:.1f} % | {100 * (cb - ca):+.1f} | "
              f"{100 * boots[:, j].std(ddof=1):.1f} |")
    print(f"mean {second} - {first} over the three rates: {100 * np.mean(diffs):+.2f} points (bootstrap SE "
          f"{100 * boots.mean(axis=1).std(ddof=1):.1f})")

if __name__ == "__main__":
    main(*sys.argv[1:])
