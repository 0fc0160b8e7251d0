"""Rule 52's decision (rule52.md), written before its sets were scored: from `station eval` of X and C on seed 1154
and on its half-panel re-render (their scores.csv and eval.json: each file's own threshold and its 1 % threshold
on its own validation set, as the note prints it), paired bootstrap SEs over the parts (1000 resamples, seed 0).
Usage: python decide52.py X_1154 C_1154 X_HALF C_HALF X_MODEL
(rules 53-55's scripts call ``decide`` with their own names, seed, shift and margin)."""

from __future__ import annotations

import csv
import json
import os
import sys

import numpy as np

from model.draem.metrics import auroc

RESAMPLES = 1000


def read(d: str) -> tuple[np.ndarray, np.ndarray, float, float]:
    """(labels, scores, the file's own threshold, its 1 % threshold on its validation set) of an eval report."""
    with open(f"{d}/scores.csv") as f:
        rows = list(csv.DictReader(f))
    ev = json.load(open(f"{d}/eval.json"))
    one = float(ev["industrial_note"].split("1 % -> ")[1].split(",")[0])
    return (np.array([int(r["label"]) for r in rows]), np.array([float(r["score"]) for r in rows]),
            float(ev["threshold"]), one)


def boot(y: np.ndarray, f, rng: np.random.Generator) -> float:
    """Bootstrap SE of the statistic ``f(idx)`` over the parts, good and defective resampled apart."""
    good, bad = np.flatnonzero(y == 0), np.flatnonzero(y == 1)
    return float(np.std([f(np.r_[rng.choice(good, len(good)), rng.choice(bad, len(bad))])
                         for _ in range(RESAMPLES)]))


def decide(y1: str, x1: str, yb: str, xb: str, model: str, names: tuple[str, str], seed: str, shift: str,
           margin: float) -> None:
    """Print a rule's table (rules 52-55 share it): candidate ``names[0]`` (reports ``y1`` on the fresh seed ``seed``
    as built, ``yb`` under ``shift``; file ``model``) against control ``names[1]`` (``x1``, ``xb``). Criterion (b)
    asks the candidate to reject at least ``margin`` fewer good parts under the shift, each at its own threshold."""
    c, k = names
    rng = np.random.default_rng(0)
    (y, sy, ty, oy), (yx, sx, tx, ox) = read(y1), read(x1)
    assert (y == yx).all(), "the same parts in the same order"
    caught = lambda s, t, i: float(np.mean(s[i][y[i] == 1] > t))  # noqa: E731
    d_caught = lambda i: caught(sy, oy, i) - caught(sx, ox, i)  # noqa: E731
    d_auroc = lambda i: auroc(y[i], sy[i]) - auroc(y[i], sx[i])  # noqa: E731
    every = np.arange(len(y))
    a1, a1se = d_caught(every), boot(y, d_caught, rng)
    a2, a2se = d_auroc(every), boot(y, d_auroc, rng)
    good = y == 0
    ry, rx = float(np.mean(sy[good] > ty)), float(np.mean(sx[good] > tx))
    (lb, by, _, _), (lbx, bx, _, _) = read(yb), read(xb)
    assert (lb == lbx).all() and (lb == y).all()
    by_rej, bx_rej = float(np.mean(by[lb == 0] > ty)), float(np.mean(bx[lb == 0] > tx))
    size = os.path.getsize(f"{model}.pt") / 1e6
    checks = {
        "(a) caught at 1 %": (a1 >= -2 * a1se, f"{c} - {k} {100 * a1:+.1f} points (SE {100 * a1se:.1f}); {c} "
                              f"{100 * caught(sy, oy, every):.1f} %, {k} {100 * caught(sx, ox, every):.1f} %"),
        "(a) image AUROC": (a2 >= -2 * a2se, f"{c} - {k} {a2:+.4f} (SE {a2se:.4f}); {c} {auroc(y, sy):.4f}, {k} "
                            f"{auroc(y, sx):.4f}"),
        f"(b) {shift}, good rejected at the own threshold": (
            bx_rej - by_rej >= margin, f"{c} {100 * by_rej:.1f} %, {k} {100 * bx_rej:.1f} %"),
        f"(c) seed {seed}, good rejected at the own threshold": (
            ry <= rx + 0.02, f"{c} {100 * ry:.1f} %, {k} {100 * rx:.1f} %"),
        "(d) size": (size <= 30.0, f"{size:.1f} MB (p99: station bench pipeline, separately)"),
    }
    print("| criterion | holds | figures |\n|---|---|---|")
    for name, (ok, text) in checks.items():
        print(f"| {name} | {'yes' if ok else 'no'} | {text} |")
    print(f"\n{c}'s threshold {ty:.4g}, {k}'s {tx:.4g}; 1 % thresholds {c} {oy:.4g}, {k} {ox:.4g}.")


if __name__ == "__main__":
    decide(*sys.argv[1:6], names=("X", "C"), seed="1154", shift="half panel", margin=0.05)
