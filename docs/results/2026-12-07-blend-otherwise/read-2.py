"""plan-2.md's reads: S against C on seed 1240 through vignetting alone, and S and C adapted on the validation set's
good parts through the whole lens chain (SA, CA) on plan.md's ALL set, beside the unadapted files there. Each file at
its stored threshold; the tests are read.py's.

    PYTHONPATH=. .venv/bin/python docs/results/2026-12-07-blend-otherwise/read-2.py > .../read-2.txt
"""
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
from read import TYPES, boot_se, load, sign_test

from model.draem.metrics import auroc

PAIRS = (("vignette", "S", "C", "vignetting alone (cos^4, 0.80 at the corners)"),
         ("allff", "S", "C", "blur, vignetting and three imperfections, files as shipped"),
         ("allff", "SA", "CA", "the same, each file adapted on the validation set's good parts under that chain"))


def main() -> None:
    print("| set | files | good | good rejected | only one (p) | caught | difference (SE) | image AUROC |")
    print("|---|---|---|---|---|---|---|---|")
    for name, a, b, label in PAIRS:
        try:
            x, y = load(a, name), load(b, name)
        except FileNotFoundError:
            print(f"| {label} | {a} / {b} | not evaluated ||||||")
            continue
        assert (x["index"] == y["index"]).all()
        lab, types = x["label"] == 1, x["type"]
        rx, ry = x["score"] > x["threshold"], y["score"] > y["threshold"]
        good = int((~lab).sum())
        ox, oy = int((rx & ~ry & ~lab).sum()), int((ry & ~rx & ~lab).sum())
        print(f"| {label} | {a} / {b} | {good} | {int(rx[~lab].sum())} / {int(ry[~lab].sum())} | {ox} / {oy} "
              f"({sign_test(ox, oy):.2g}) | {rx[lab].mean():.1%} / {ry[lab].mean():.1%} | "
              f"{rx[lab].mean() - ry[lab].mean():+.1%} ({boot_se(rx[lab].astype(float), ry[lab].astype(float)):.1%}) "
              f"| {auroc(lab, x['score']):.3f} / {auroc(lab, y['score']):.3f} |")
        for m, r in ((a, rx), (b, ry)):
            print(f"|  | {m} by type | | | | " + ", ".join(f"{t} {r[types == t].mean():.0%}" for t in TYPES
                                                          if (types == t).any()) + " | | |")


if __name__ == "__main__":
    main()
