"""plan.md's reads on the fresh sets B, N, G and R: C (the shipped cascade) against D, each at its thresholds from the
validation set; paired bootstrap SEs over the parts (2000 draws). Writes read.txt's lines and read.json. Run from the
repository's root after arrays.py on the four sets."""
import json
from functools import partial
from pathlib import Path

import numpy as np
from decide import cascade, load, mean, thresholds
from sklearn.metrics import roc_auc_score

HERE = Path(__file__).parent
SETS = {"B": "look-built-1222_test", "N": "look-new-kinds-1223_test", "G": "look-ggx-1224_test",
        "R": "look-rough-1224_test"}
DECISIONS = {"C": cascade, "D": mean, "network alone": partial(mean, weight=0.0)}
THRESHOLDS = {n: thresholds(f) for n, f in DECISIONS.items()}
rng = np.random.default_rng(0)


def paired_se(a: np.ndarray, b: np.ndarray) -> float:
    """Bootstrap SE of mean(b) - mean(a) over paired 0/1 outcomes."""
    i = rng.integers(0, len(a), (2000, len(a)))
    return float((b[i].mean(1) - a[i].mean(1)).std())


out: dict = {}
for tag, name in SETS.items():
    a = load(name)
    lab, kind = a["label"], a["kind"]
    print(f"\n{tag} ({name}): {(~lab).sum()} good, {lab.sum()} defective")
    res = {}
    for n, f in DECISIONS.items():
        s, (t1, t5) = f(a), THRESHOLDS[n]
        r = {"caught_1": float(np.mean(s[lab] > t1)), "caught_5": float(np.mean(s[lab] > t5)),
             "good_rejected": int(np.sum(s[~lab] > t1)), "good": int((~lab).sum()),
             "auroc": float(roc_auc_score(lab, s)) if 0 < lab.sum() < len(lab) else None,
             "hit_1": (s[lab] > t1), "hit_5": (s[lab] > t5), "types": {}}
        for k in sorted(set(kind[lab])):
            m = lab & (kind == k)
            r["types"][k] = {"n": int(m.sum()), "caught_1": float(np.mean(s[m] > t1)),
                             "caught_5": float(np.mean(s[m] > t5)),
                             "auroc": float(roc_auc_score(np.r_[np.zeros((~lab).sum()), np.ones(m.sum())],
                                                          np.r_[s[~lab], s[m]]))}
        res[n] = r
        per = "; ".join(f"{k} {v['caught_1']:.0%} / {v['caught_5']:.0%} / {v['auroc']:.3f}"
                        for k, v in r["types"].items())
        auroc = "" if r["auroc"] is None else f", image AUROC {r['auroc']:.3f}"
        print(f"  {n:14s} caught at 1 % {r['caught_1']:6.1%}, at 5 % {r['caught_5']:6.1%}; good rejected "
              f"{r['good_rejected']} of {r['good']}{auroc}\n      per type (1 % / 5 % / AUROC): {per}")
    for level in ("1", "5"):
        d = res["D"][f"hit_{level}"].astype(float) - res["C"][f"hit_{level}"].astype(float)
        se = paired_se(res["C"][f"hit_{level}"].astype(float), res["D"][f"hit_{level}"].astype(float))
        res[f"D-C_{level}"] = {"diff": float(d.mean()), "se": se}
        print(f"  D - C caught at {level} %: {d.mean():+.1%} (paired SE {se:.1%})")
    out[tag] = {n: {k: v for k, v in r.items() if not k.startswith("hit")} if "types" in r else r
                for n, r in res.items()}

b, n, g, r = (out[t] for t in "BNGR")
checks = {
    "1 primary: B, D catches more at 1 % by >= 1.5 paired SE": b["D-C_1"]["diff"] >= 1.5 * b["D-C_1"]["se"],
    "2a: B, D rejects <= 2 % of good parts": b["D"]["good_rejected"] <= 0.02 * b["D"]["good"],
    "2b: N, D catches >= C - 1 paired SE at 1 %": n["D-C_1"]["diff"] >= -n["D-C_1"]["se"],
    "2c: G, D rejects <= C + 1 and <= 3 %": (g["D"]["good_rejected"] <= g["C"]["good_rejected"] + 1
                                            and g["D"]["good_rejected"] <= 0.03 * g["D"]["good"]),
    "2c: R, D rejects <= C + 1 and <= 3 %": (r["D"]["good_rejected"] <= r["C"]["good_rejected"] + 1
                                            and r["D"]["good_rejected"] <= 0.03 * r["D"]["good"]),
    "2d: B, D catches >= C - 1 paired SE at 5 %": b["D-C_5"]["diff"] >= -b["D-C_5"]["se"],
}
print()
for k, v in checks.items():
    print(f"{'holds' if v else 'FAILS'}: {k}")
print("taken" if all(checks.values()) else "not taken")
out["checks"] = {k: bool(v) for k, v in checks.items()}
(HERE / "read.json").write_text(json.dumps(out, indent=1))
