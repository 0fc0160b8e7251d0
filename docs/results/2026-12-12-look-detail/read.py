"""plan.md's screen: the recipe at --size 128 (draws d0, d2) against make model's three draws at 96 (m0, m1, m2),
from per-part dumps (dump.py here; ../2026-12-12-look-ensemble/dump.py for the 96 draws), each file scored,
blended and thresholded as the recipe does (../2026-12-12-look-ensemble/aggregate.py). Writes read.txt.

    PYTHONPATH=. .venv/bin/python docs/results/2026-12-12-look-detail/read.py"""
import contextlib
import importlib.util
from pathlib import Path

import numpy as np
from sklearn.metrics import roc_auc_score

HERE = Path(__file__).parent
_spec = importlib.util.spec_from_file_location("aggregate", HERE.parent / "2026-12-12-look-ensemble/aggregate.py")
agg = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(agg)

ARMS = {"96 m0": ("runs/look-ens/dump", "runs/look-ens/E3", "m0"),
        "96 m1": ("runs/look-ens/dump", "runs/look-ens/E3", "m1"),
        "96 m2 (shipped)": ("runs/look-ens/dump", "runs/look-ens/E3", "m2"),
        "128 d0": ("runs/size128/dump-d0", "runs/size128/look-0", "m0"),
        "128 d2": ("runs/size128/dump-d2", "runs/size128/look-2", "m0")}
BUILT = ("built-1245", "built-1247")


def main() -> None:
    rows = {}
    for arm, (dump, model, join) in ARMS.items():
        jd = agg.Joined(Path(dump), model)
        sc, thr = jd.scores(join)
        s = np.concatenate([sc[n] for n in BUILT])
        lab = np.concatenate([jd.sets[n]["label"] for n in BUILT])
        typ = np.concatenate([jd.sets[n]["defect_type"] for n in BUILT])
        g = lab == 0
        ds = g | np.isin(typ, ["dent", "scratch"])
        r = {"good rejected as built": f"{int((s[g] > thr).sum())}/{int(g.sum())}",
             "caught as built": f"{(s[lab == 1] > thr).mean() * 100:.1f} %",
             "matched 1-5 %": agg.matched(s, lab),
             "dents+scratches AUROC": roc_auc_score(lab[ds], s[ds]),
             "dents": roc_auc_score(lab[g | (typ == "dent")], s[g | (typ == "dent")]),
             "scratches": roc_auc_score(lab[g | (typ == "scratch")], s[g | (typ == "scratch")]),
             "image AUROC": roc_auc_score(lab, s)}
        for n in ("allff-1245", "allff-1247", "vallens", "new-1248"):
            lb = jd.sets[n]["label"]
            r[f"{n} good rejected"] = f"{int((sc[n][lb == 0] > thr).sum())}/{int((lb == 0).sum())}"
        lb = jd.sets["new-1248"]["label"]
        r["new kinds matched 1-5 %"] = agg.matched(sc["new-1248"], lb)
        rows[arm] = r
    keys = list(next(iter(rows.values())))
    print("| measure (seeds 1245 + 1247 as built pooled unless named) | " + " | ".join(rows) + " |")
    print("|---|" + "---|" * len(rows))
    for k in keys:
        vals = [rows[a][k] for a in rows]
        print(f"| {k} | " + " | ".join(v if isinstance(v, str) else f"{v:.3f}" if v < 1.5 else f"{v:.1f}"
                                      for v in vals) + " |")
    m96 = np.mean([rows[a]["matched 1-5 %"] for a in rows if a.startswith("96")])
    m128 = np.mean([rows[a]["matched 1-5 %"] for a in rows if a.startswith("128")])
    a96 = np.mean([rows[a]["dents+scratches AUROC"] for a in rows if a.startswith("96")])
    a128 = np.mean([rows[a]["dents+scratches AUROC"] for a in rows if a.startswith("128")])
    print(f"\nmean of draws: matched 1-5 % 128 {m128:.1f} vs 96 {m96:.1f} ({m128 - m96:+.1f}; plan asks +3); "
          f"dents+scratches AUROC 128 {a128:.3f} vs 96 {a96:.3f} ({a128 - a96:+.3f}; plan asks +0.03)")


if __name__ == "__main__":
    with open(HERE / "read.txt", "w") as f, contextlib.redirect_stdout(f):
        main()
