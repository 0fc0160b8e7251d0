"""Report of flow52.py's OUT.npz: for each fit, the window alone and the cascade without a network (above the gate
the larger of window and test), thresholds at 1 % and 5 % of the good validation parts, on the held-out sets
pooled: caught, good rejected, image AUROC, per type. Usage: PYTHONPATH=. python report52.py OUT.npz..."""

from __future__ import annotations

import sys

import numpy as np

from model.draem.metrics import auroc, false_reject_threshold

TYPES = ("chip", "dent", "missing_stud", "scratch", "stain")


def report(path: str) -> None:
    d = np.load(path)
    held = sorted({k.split("_")[1] for k in d.files if k.startswith("A_h") and k.endswith("_window")})
    print(f"## {path} (held-out: {', '.join(held)})\n")
    print("| fit | score | caught at 1 % | good rejected | caught at 5 % | good rejected | AUROC | "
          + " | ".join(f"{t} at 1 %" for t in TYPES) + " |")
    print("|---|---|---|---|---|---|---|" + "---|" * len(TYPES))
    lab = np.concatenate([d[f"{s}_label"] for s in held])
    typ = np.concatenate([d[f"{s}_type"] for s in held])
    vg = d["val_label"] == 0
    for fit in ("A", "B"):
        gate = float(d[f"{fit}_gate"])

        def score(s: str, kind: str, fit: str = fit, gate: float = gate) -> np.ndarray:
            w, c = d[f"{fit}_{s}_window"], d[f"{fit}_{s}_chi"]
            return w if kind == "window" else np.where(w > gate, np.maximum(w, c), w)
        for kind in ("window", "cascade"):
            v = score("val", kind)[vg]
            x = np.concatenate([score(s, kind) for s in held])
            cells = []
            for rate in (0.01, 0.05):
                t = false_reject_threshold(v, rate)
                cells += [f"{(x[lab == 1] > t).mean():.1%}", f"{(x[lab == 0] > t).mean():.1%}"]
            t1 = false_reject_threshold(v, 0.01)
            per = [f"{(x[typ == ty] > t1).mean():.0%}" for ty in TYPES]
            print(f"| {fit} | {kind} | " + " | ".join(cells) + f" | {auroc(lab, x):.3f} | " + " | ".join(per) + " |")
    print()


for p in sys.argv[1:]:
    report(p)
