"""The good validation and held-out parts at the top of fit A's window scores, and their window scores under fit B
(flow52.py's OUT.npz), highest of A first. Usage: PYTHONPATH=. python tail52.py OUT.npz..."""

from __future__ import annotations

import sys

import numpy as np

for path in sys.argv[1:]:
    d = np.load(path)
    print(f"## {path}\n")
    print("| set | the 8 highest good parts under A | the same parts under B | the 6 highest good parts under B |")
    print("|---|---|---|---|")
    for s in ("val", "h0", "h1"):
        g = d[f"{s}_label"] == 0
        a, b = d[f"A_{s}_window"][g], d[f"B_{s}_window"][g]
        top = np.argsort(-a, kind="stable")[:8]
        fmt = lambda v: " ".join(f"{x:.1f}" for x in v)  # noqa: E731
        print(f"| {s} | {fmt(a[top])} | {fmt(b[top])} | {fmt(np.sort(b)[::-1][:6])} |")
    print()
