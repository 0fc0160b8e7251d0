"""Rule 53's decision (rule53.md), written before its sets were scored: from `station eval` of Y and X on seed 1156
and on its 0.7 px lens re-exposure (each file's own threshold and its 1 % threshold on its own validation set),
paired bootstrap SEs over the parts, read and resampled as rule 52's decide52.py does.
Usage: PYTHONPATH=. python decide53.py Y_1156 X_1156 Y_BLUR X_BLUR Y_MODEL
(rule 54's decide54.py calls ``decide`` with its own names, set and shift)."""

from __future__ import annotations

import os
import sys
from pathlib import Path

import numpy as np

from model.draem.metrics import auroc

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "2026-11-29-panel-brightness"))
from decide52 import boot, read


def decide(y1: str, x1: str, yb: str, xb: str, model: str, names: tuple[str, str] = ("Y", "X"),
           seed: str = "1156", shift: str = "0.7 px lens") -> None:
    """Print the rule's table: candidate ``names[0]`` (reports ``y1`` as built, ``yb`` shifted; file ``model``)
    against control ``names[1]`` (``x1``, ``xb``)."""
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
            bx_rej - by_rej >= 0.03, f"{c} {100 * by_rej:.1f} %, {k} {100 * bx_rej:.1f} %"),
        f"(c) seed {seed}, good rejected at the own threshold": (
            ry <= rx + 0.02, f"{c} {100 * ry:.1f} %, {k} {100 * rx:.1f} %"),
        "(d) size": (size <= 30.0, f"{size:.1f} MB (p99: station bench pipeline, separately)"),
    }
    print("| criterion | holds | figures |\n|---|---|---|")
    for name, (ok, text) in checks.items():
        print(f"| {name} | {'yes' if ok else 'no'} | {text} |")
    print(f"\n{c}'s threshold {ty:.4g}, {k}'s {tx:.4g}; 1 % thresholds {c} {oy:.4g}, {k} {ox:.4g}.")


if __name__ == "__main__":
    decide(*sys.argv[1:6])
