"""Plan 68's table: each file at its own stored threshold on each set of seed 1188 (plan.md).

    PYTHONPATH=. python table.py runs/r68 > table.md"""
import json
import sys
from pathlib import Path

import numpy as np

from model.draem.metrics import rank_auroc
from station.eval_compare import read_scores

SETS = (("as built", "line-panel-heldout-1188"), ("GGX microfacets", "om-ggx-1188"),
        ("a duller plastic (alpha 0.02-0.04)", "om-rough-1188"), ("the panel at half its radiance", "pb-half-1188"),
        ("a lens blur of 0.7 px", "so-blurff-1188"), ("the blur and four more imperfections", "so-allff-1188"))
FILES = ("E63", "F63")
runs = Path(sys.argv[1])
out = {}


def report(d: Path) -> tuple[float, list, np.ndarray, np.ndarray] | None:
    """An eval folder's stored threshold, its (label, type, score) rows, labels and scores; None if not measured."""
    if not (d / "eval.json").exists():
        return None
    rows = list(read_scores(d).values())
    return (float(json.loads((d / "eval.json").read_text())["threshold"]), rows,
            np.array([label for label, _, _ in rows]), np.array([score for _, _, score in rows]))


print("| set | file | good parts rejected | defective parts caught | image AUROC |")
print("|---|---|---|---|---|")
for name, data in SETS:
    for f in FILES:
        r = report(runs / f"eval-{f}-{data}")
        if r is None:
            print(f"| {name} | {f} | not measured | | |")
            continue
        th, _, y, s = r
        good, bad = s[y == 0], s[y == 1]
        k = int((good > th).sum())
        out[f"{f}/{data}"] = {"threshold": th, "good": len(good), "good_rejected": k,
                              "defective": len(bad), "caught": int((bad > th).sum()), "auroc": rank_auroc(y, s)}
        print(f"| {name} | {f} | {100 * k / len(good):.1f} % ({k} of {len(good)}) | "
              f"{100 * (bad > th).mean():.1f} % | {rank_auroc(y, s):.3f} |")
print()
print("| kinds nobody rendered (seed 1189) | file | good parts rejected | blisters caught | particles caught "
      "| image AUROC |")
print("|---|---|---|---|---|---|")
for f in FILES:
    r = report(runs / f"eval-{f}-new-kinds-1189")
    if r is None:
        print(f"| | {f} | not measured | | | |")
        continue
    th, rows, y, s = r
    good = s[y == 0]
    kinds = {t: np.array([score > th for label, kind, score in rows if label == 1 and kind == t])
             for t in ("blister", "debris")}
    k = int((good > th).sum())
    out[f"{f}/new-kinds-1189"] = {"threshold": th, "good": len(good), "good_rejected": k,
                                  **{t: [int(c.sum()), len(c)] for t, c in kinds.items()}, "auroc": rank_auroc(y, s)}
    print(f"| | {f} | {100 * k / len(good):.1f} % ({k} of {len(good)}) | "
          + " | ".join(f"{100 * c.mean():.1f} % ({int(c.sum())} of {len(c)})" for c in kinds.values())
          + f" | {rank_auroc(y, s):.3f} |")
(runs / "table.json").write_text(json.dumps(out, indent=1))
