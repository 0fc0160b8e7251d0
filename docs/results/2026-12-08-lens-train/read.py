"""plan.md's read: candidate L (trained through a drawn lens) against the shipped file S on fresh sets B (seed 1241 as
built), V (B through the whole lens chain) and N (seed 1242, kinds nobody rendered), each file at its stored threshold
and at matched rates of good parts rejected (the threshold from the set's own good parts); then the plan's four bars.

    PYTHONPATH=. .venv/bin/python docs/results/2026-12-08-lens-train/read.py > .../read.txt

Writes read.json beside it. Loading, the sign test and the bootstrap are stop 124's
(../2026-12-07-blend-otherwise/read.py, ../2026-12-07-matched-rates/curves.py)."""
import importlib.util
import json
import sys
from pathlib import Path

import numpy as np

from model.draem.metrics import auroc

HERE = Path(__file__).parent
sys.path.insert(0, str(HERE.parent / "2026-12-07-matched-rates"))
from curves import RATES, caught_at, matched  # noqa: E402

_spec = importlib.util.spec_from_file_location("earlier", HERE.parent / "2026-12-07-blend-otherwise/read.py")
_earlier = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(_earlier)
_earlier.HERE = HERE  # its load() reads HERE / "eval" / f"{model}-{name}"
load, boot_se, sign_test, TYPES, PROMISE = (_earlier.load, _earlier.boot_se, _earlier.sign_test, _earlier.TYPES,
                                            _earlier.PROMISE)
SETS = {"built-1241": "B: as built (seed 1241)", "allff-1241": "V: B through blur, vignetting, three imperfections",
        "new-1242": "N: kinds nobody rendered (seed 1242)"}
MODELS = ("S", "L")


def read(name: str) -> dict:
    d = {m: load(m, name) for m in MODELS}
    assert (d["S"]["index"] == d["L"]["index"]).all() and (d["S"]["label"] == d["L"]["label"]).all()
    y, types = d["S"]["label"], d["S"]["type"]
    res: dict = {"good": int((y == 0).sum()), "defective": int((y == 1).sum())}
    rej = {m: d[m]["score"] > d[m]["threshold"] for m in MODELS}
    for m in MODELS:
        s = d[m]["score"]
        kinds = sorted({t for t in types[y == 1]})
        res[m] = {"good_rejected": int(rej[m][y == 0].sum()), "caught": float(rej[m][y == 1].mean()),
                  "auroc": auroc(y, s), "threshold": d[m]["threshold"],
                  "matched": [caught_at(s[y == 0], s[y == 1], r) for r in RATES],
                  "caught_by_type": {t: float(rej[m][types == t].mean()) for t in kinds},
                  "auroc_by_type": {t: auroc(y[(y == 0) | (types == t)], s[(y == 0) | (types == t)]) for t in kinds}}
        res[m]["matched_mean"] = float(np.mean(res[m]["matched"]))
    only_l = int((rej["L"] & ~rej["S"] & (y == 0)).sum())
    only_s = int((rej["S"] & ~rej["L"] & (y == 0)).sum())
    res["good_only_L"], res["good_only_S"], res["good_sign_p"] = only_l, only_s, sign_test(only_l, only_s)
    res["caught_diff_se"] = boot_se(rej["L"][y == 1].astype(float), rej["S"][y == 1].astype(float))
    return res


def main() -> None:
    out: dict = {}
    print("| set | good | S: good rejected | L: good rejected | only L / only S (p) | S: caught | L: caught | "
          "L - S (SE) | S: AUROC | L: AUROC |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for name, label in SETS.items():
        if not all((HERE / "eval" / f"{m}-{name}" / "scores.csv").exists() for m in MODELS):
            print(f"| {label} | not evaluated |||||||||")
            continue
        r = out[name] = read(name)
        s, lo = r["S"], r["L"]
        print(f"| {label} | {r['good']} | {s['good_rejected']} ({s['good_rejected'] / r['good']:.1%}) | "
              f"{lo['good_rejected']} ({lo['good_rejected'] / r['good']:.1%}) | {r['good_only_L']} / "
              f"{r['good_only_S']} ({r['good_sign_p']:.2g}) | {s['caught']:.1%} | {lo['caught']:.1%} | "
              f"{lo['caught'] - s['caught']:+.1%} ({r['caught_diff_se']:.1%}) | {s['auroc']:.3f} | {lo['auroc']:.3f} |")
    for name, r in out.items():
        print(f"\n== {SETS[name]}: caught at the stored threshold / image AUROC per type")
        print("| type | S caught | L caught | S AUROC | L AUROC |\n|---|---|---|---|---|")
        for t in r["S"]["caught_by_type"]:
            print(f"| {t} | {r['S']['caught_by_type'][t]:.1%} | {r['L']['caught_by_type'][t]:.1%} | "
                  f"{r['S']['auroc_by_type'][t]:.3f} | {r['L']['auroc_by_type'][t]:.3f} |")
        print()
        d = {m: load(m, name) for m in MODELS}
        matched(d["S"]["score"], d["L"]["score"], d["S"]["label"] == 1, ("S", "L"))
    bars = {}
    if {"allff-1241", "built-1241", "new-1242"} <= out.keys():
        v, b, n = out["allff-1241"], out["built-1241"], out["new-1242"]
        bars = {"1 V: L good rejected <= 2.1 %": v["L"]["good_rejected"] / v["good"] <= PROMISE,
                "2 B: L matched mean >= S's - 1 point": b["L"]["matched_mean"] >= b["S"]["matched_mean"] - 0.01,
                "3 B: L good rejected <= 2.1 %": b["L"]["good_rejected"] / b["good"] <= PROMISE,
                "4 N: L matched mean >= S's - 2 points": n["L"]["matched_mean"] >= n["S"]["matched_mean"] - 0.02}
        print("\n== the plan's bars")
        for k, ok in bars.items():
            print(f"- {k}: {'holds' if ok else 'FAILS'}")
    (HERE / "read.json").write_text(json.dumps({"sets": out, "bars": bars}, indent=1))


if __name__ == "__main__":
    main()
