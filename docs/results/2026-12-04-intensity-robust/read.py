"""The plan's reads (plan.md): R (intensity alone) against the shipped file E63 on seed 1193 rendered three ways.

    PYTHONPATH=. .venv/bin/python docs/results/2026-12-04-intensity-robust/read.py > .../read.txt

Each file at its stored threshold (a part is rejected when its score is above it). Writes read.json beside it.
"""
import csv
import json
from math import comb
from pathlib import Path

import numpy as np

from model.draem.metrics import auroc

HERE = Path(__file__).parent
RENDERINGS = {"built": "as built", "ggx": "GGX lobe", "rough": "duller plastic"}
MODELS = ("R", "E63")
TYPES = ("chip", "dent", "missing_stud", "scratch", "stain")


def load(model: str, rendering: str) -> dict:
    folder = HERE / "eval" / f"{model}-{rendering}"
    rows = sorted(csv.DictReader(open(folder / "scores.csv")), key=lambda r: int(r["index"]))
    return {"index": np.array([int(r["index"]) for r in rows]), "label": np.array([int(r["label"]) for r in rows]),
            "type": np.array([r["defect_type"] for r in rows]), "score": np.array([float(r["score"]) for r in rows]),
            "threshold": json.load(open(folder / "eval.json"))["threshold"]}


def sign_test(a: int, b: int) -> float:
    """Exact two-sided sign test: the chance of a split at least as uneven as a:b among a + b discordant pairs."""
    n, k = a + b, min(a, b)
    return min(1.0, 2 * sum(comb(n, i) for i in range(k + 1)) / 2**n) if n else 1.0


def boot_se(x: np.ndarray, y: np.ndarray, reps: int = 2000) -> float:
    """Bootstrap SE over parts of mean(x) - mean(y), x and y paired per part."""
    rng = np.random.default_rng(0)
    idx = rng.integers(0, len(x), (reps, len(x)))
    return float((x[idx].mean(1) - y[idx].mean(1)).std())


def main() -> None:
    out: dict = {}
    for key, name in RENDERINGS.items():
        d = {m: load(m, key) for m in MODELS}
        assert (d["R"]["index"] == d["E63"]["index"]).all() and (d["R"]["label"] == d["E63"]["label"]).all()
        y = d["R"]["label"]
        rej = {m: d[m]["score"] > d[m]["threshold"] for m in MODELS}
        k_e63 = int(rej["E63"][y == 0].sum())
        res: dict = {"good": int((y == 0).sum()), "defective": int((y == 1).sum())}
        for m in MODELS:
            s = d[m]["score"]
            good = np.sort(s[y == 0])[::-1]
            res[m] = {"good_rejected": int(rej[m][y == 0].sum()), "caught": float(rej[m][y == 1].mean()),
                      "auroc": auroc(y, s),
                      "caught_at_e63_count": float((s[y == 1] > good[k_e63]).mean()),
                      "auroc_by_type": {t: auroc(y[(y == 0) | (d[m]["type"] == t)],
                                                  s[(y == 0) | (d[m]["type"] == t)]) for t in TYPES}}
        res["caught_diff_se"] = boot_se(rej["R"][y == 1].astype(float), rej["E63"][y == 1].astype(float))
        res["good_only_R"] = int((rej["R"] & ~rej["E63"])[y == 0].sum())
        res["good_only_E63"] = int((rej["E63"] & ~rej["R"])[y == 0].sum())
        out[key] = res
        print(f"{name} ({res['good']} good, {res['defective']} defective)")
        for m in MODELS:
            r = res[m]
            print(f"  {m:4s} {r['good_rejected']:3d} good rejected, {100 * r['caught']:.1f} % caught, AUROC "
                  f"{r['auroc']:.3f}; caught at {k_e63} good rejected {100 * r['caught_at_e63_count']:.1f} %; by type "
                  + ", ".join(f"{t} {v:.3f}" for t, v in r["auroc_by_type"].items()))
        print(f"  caught R - E63 {100 * (res['R']['caught'] - res['E63']['caught']):+.1f} points "
              f"(SE {100 * res['caught_diff_se']:.1f}); good rejected by R only {res['good_only_R']}, "
              f"by E63 only {res['good_only_E63']}")
    a = sum(out[k]["good_only_R"] for k in ("ggx", "rough"))
    b = sum(out[k]["good_only_E63"] for k in ("ggx", "rough"))
    r_sum = sum(out[k]["R"]["good_rejected"] for k in ("ggx", "rough"))
    e_sum = sum(out[k]["E63"]["good_rejected"] for k in ("ggx", "rough"))
    p = sign_test(a, b)
    primary = r_sum < e_sum and p < 0.05
    built = out["built"]
    guard_rejects = built["R"]["good_rejected"] <= built["E63"]["good_rejected"] + 2
    guard_caught = built["R"]["caught"] >= built["E63"]["caught"] - 0.05
    out["verdict"] = {"R_rejected_otherwise": r_sum, "E63_rejected_otherwise": e_sum, "discordant_R_only": a,
                      "discordant_E63_only": b, "sign_test_p": p, "primary": primary,
                      "guard_rejects": guard_rejects, "guard_caught": guard_caught,
                      "holds_better": primary and guard_rejects and guard_caught}
    print(f"primary: otherwise R rejected {r_sum}, E63 {e_sum} of {2 * built['good']}; discordant {a} (R only) : "
          f"{b} (E63 only), sign test p = {p:.3g} -> {'holds' if primary else 'does not hold'}")
    print(f"guards as built: rejects {'hold' if guard_rejects else 'fail'}, caught "
          f"{'holds' if guard_caught else 'fails'}; R holds better: {out['verdict']['holds_better']}")
    (HERE / "read.json").write_text(json.dumps(out, indent=1) + "\n")


if __name__ == "__main__":
    main()
