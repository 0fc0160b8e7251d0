"""Rule 59's decision (rule59.md), written before seed 1160 was scored: from `station eval` of K and C on seed 1160
(scores.csv and eval.json: each file's own threshold), and of K on the two guard sets; paired bootstrap SEs over
the parts (``decide52.boot``). Usage (from the repository root, PYTHONPATH=.):
python decide59.py K_1160 C_1160 K_HALF K_IMPERFECT K_MODEL"""

from __future__ import annotations

import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "2026-11-29-panel-brightness"))
from decide52 import boot, read

from model.draem.metrics import auroc

TYPES = ("chip", "dent", "missing_stud", "scratch", "stain")


def types_of(d: str) -> np.ndarray:
    import csv
    with open(f"{d}/scores.csv") as f:
        return np.array([r.get("defect_type") or r.get("defect") or "" for r in csv.DictReader(f)])


def main(k1: str, c1: str, k_half: str, k_imp: str, model: str) -> None:
    rng = np.random.default_rng(0)
    (y, sk, tk, _), (yc, sc, tc, _) = read(k1), read(c1)
    assert (y == yc).all(), "the same parts in the same order"
    every, good = np.arange(len(y)), y == 0
    caught = lambda s, t, i: float(np.mean(s[i][y[i] == 1] > t))  # noqa: E731
    d_caught = lambda i: caught(sk, tk, i) - caught(sc, tc, i)  # noqa: E731
    d_auroc = lambda i: auroc(y[i], sk[i]) - auroc(y[i], sc[i])  # noqa: E731
    a, ase = d_caught(every), boot(y, d_caught, rng)
    u, use = d_auroc(every), boot(y, d_auroc, rng)
    rk, rc = float(np.mean(sk[good] > tk)), float(np.mean(sc[good] > tc))
    guards = []
    for d in (k_half, k_imp):
        lg, sg, tg, _ = read(d)
        guards.append(float(np.mean(sg[lg == 0] > tg)))
    size = os.path.getsize(f"{model}.pt") / 1e6
    checks = {
        "(a) caught at the own threshold": (
            a > 0 and a >= 2 * ase, f"K - C {100 * a:+.1f} points (SE {100 * ase:.1f}); "
                                    f"K {100 * caught(sk, tk, every):.1f} %, C {100 * caught(sc, tc, every):.1f} %"),
        "(b) good rejected at the own threshold": (rk <= rc + 0.015, f"K {100 * rk:.1f} %, C {100 * rc:.1f} %"),
        "(c) image AUROC": (u >= -2 * use,
                            f"K - C {u:+.4f} (SE {use:.4f}); K {auroc(y, sk):.4f}, C {auroc(y, sc):.4f}"),
        "(d) guards, good rejected at K's threshold": (
            guards[0] <= 0.03 and guards[1] <= 0.05,
            f"half panel (1154) {100 * guards[0]:.1f} % (C 0.6 %), imperfect camera (1159) {100 * guards[1]:.1f} % "
            f"(C 3.1 %)"),
        "(e) size": (size <= 30.0, f"{size:.1f} MB (p99: station bench pipeline, separately)"),
    }
    print("| criterion | holds | figures |\n|---|---|---|")
    for name, (ok, text) in checks.items():
        print(f"| {name} | {'yes' if ok else 'no'} | {text} |")
    print(f"\nK's threshold {tk:.4g}, C's {tc:.4g}.\n")
    t = types_of(k1)
    print("| type | n | K caught | C caught | K AUROC | C AUROC |\n|---|---|---|---|---|---|")
    for d in TYPES:
        m = t == d
        if m.any():
            g = m | good
            print(f"| {d} | {int(m.sum())} | {100 * np.mean(sk[m] > tk):.0f} % | {100 * np.mean(sc[m] > tc):.0f} % | "
                  f"{auroc(y[g], sk[g]):.3f} | {auroc(y[g], sc[g]):.3f} |")


if __name__ == "__main__":
    main(*sys.argv[1:6])
