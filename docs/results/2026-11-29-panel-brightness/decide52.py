"""Rule 52's decision (rule52.md), written before its sets were scored: from `station eval` of X and C on seed 1154
and on its half-panel re-render (their scores.csv and eval.json: each file's own threshold and its 1 % threshold
on its own validation set, as the note prints it), paired bootstrap SEs over the parts (1000 resamples, seed 0).
Usage: python decide52.py X_1154 C_1154 X_HALF C_HALF X_MODEL"""

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


def main() -> None:
    x1, c1, xh, ch, model = sys.argv[1:6]
    rng = np.random.default_rng(0)
    (y, sx, tx, ox), (yc, sc, tc, oc) = read(x1), read(c1)
    assert (y == yc).all(), "the same parts in the same order"
    caught = lambda s, t, i: float(np.mean(s[i][y[i] == 1] > t))  # noqa: E731
    d_caught = lambda i: caught(sx, ox, i) - caught(sc, oc, i)  # noqa: E731
    d_auroc = lambda i: auroc(y[i], sx[i]) - auroc(y[i], sc[i])  # noqa: E731
    every = np.arange(len(y))
    a1, a1se = d_caught(every), boot(y, d_caught, rng)
    a2, a2se = d_auroc(every), boot(y, d_auroc, rng)
    good = y == 0
    cx, cc = float(np.mean(sx[good] > tx)), float(np.mean(sc[good] > tc))
    (yh, hx, _, _), (yhc, hc, _, _) = read(xh), read(ch)
    assert (yh == yhc).all() and (yh == y).all()
    hx_rej, hc_rej = float(np.mean(hx[yh == 0] > tx)), float(np.mean(hc[yh == 0] > tc))
    size = os.path.getsize(f"{model}.pt") / 1e6
    checks = {
        "(a) caught at 1 %": (a1 >= -2 * a1se, f"X - C {100 * a1:+.1f} points (SE {100 * a1se:.1f}); X "
                              f"{100 * caught(sx, ox, every):.1f} %, C {100 * caught(sc, oc, every):.1f} %"),
        "(a) image AUROC": (a2 >= -2 * a2se, f"X - C {a2:+.4f} (SE {a2se:.4f}); X {auroc(y, sx):.4f}, C "
                            f"{auroc(y, sc):.4f}"),
        "(b) half panel, good rejected at the own threshold": (
            hc_rej - hx_rej >= 0.05, f"X {100 * hx_rej:.1f} %, C {100 * hc_rej:.1f} %"),
        "(c) seed 1154, good rejected at the own threshold": (
            cx <= cc + 0.02, f"X {100 * cx:.1f} %, C {100 * cc:.1f} %"),
        "(d) size": (size <= 30.0, f"{size:.1f} MB (p99: station bench pipeline, separately)"),
    }
    print("| criterion | holds | figures |\n|---|---|---|")
    for name, (ok, text) in checks.items():
        print(f"| {name} | {'yes' if ok else 'no'} | {text} |")
    print(f"\nX's threshold {tx:.4g}, C's {tc:.4g}; 1 % thresholds X {ox:.4g}, C {oc:.4g}.")


if __name__ == "__main__":
    main()
