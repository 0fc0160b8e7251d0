"""Rule 56's decision (rule56.md), written before seed 1159 was scored: the shipped file's 1 % threshold (T1) against
its shipped threshold (T5), both read from one `station eval` report per set, paired bootstrap SEs over the parts
(decide52.py's ``read`` and ``boot``). Usage: PYTHONPATH=. python decide56.py X_1159 X_ALL"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "2026-11-29-panel-brightness"))
from decide52 import boot, read


def shares(y: np.ndarray, s: np.ndarray, t: float, i: np.ndarray) -> tuple[float, float]:
    """(good rejected, defective caught) among parts ``i`` at threshold ``t``."""
    y, s = y[i], s[i]
    return float(np.mean(s[y == 0] > t)), float(np.mean(s[y == 1] > t))


def main(built: str, shifted: str) -> None:
    rng = np.random.default_rng(0)
    rows, rejected = [], {}
    for name, d in (("seed 1159 as built", built), ("seed 1159, all five imperfections", shifted)):
        y, s, t5, t1 = read(d)
        every = np.arange(len(y))
        for rule, t in (("T1", t1), ("T5", t5)):
            g, c = shares(y, s, t, every)
            gse = boot(y, lambda i, y=y, s=s, t=t: shares(y, s, t, i)[0], rng)
            cse = boot(y, lambda i, y=y, s=s, t=t: shares(y, s, t, i)[1], rng)
            rejected[name, rule] = g
            rows.append(f"| {name} | {rule} ({t:.4g}) | {100 * g:.1f} % (SE {100 * gse:.1f}) | "
                        f"{100 * c:.1f} % (SE {100 * cse:.1f}) |")
    print("| set | threshold | good rejected | defective caught |\n|---|---|---|---|")
    print("\n".join(rows))
    a = rejected["seed 1159 as built", "T1"]
    b1 = rejected["seed 1159, all five imperfections", "T1"]
    b5 = rejected["seed 1159, all five imperfections", "T5"]
    print("\n| criterion | holds | figures |\n|---|---|---|")
    print(f"| (a) as built, T1 rejects <= 3 % of good parts | {'yes' if a <= 0.03 else 'no'} | {100 * a:.1f} % |")
    ok = b1 <= 0.05 and b5 - b1 >= 0.05
    print(f"| (b) all five, T1 <= 5 % and >= 5 points below T5 | {'yes' if ok else 'no'} | T1 {100 * b1:.1f} %, "
          f"T5 {100 * b5:.1f} % |")


if __name__ == "__main__":
    main(*sys.argv[1:3])
