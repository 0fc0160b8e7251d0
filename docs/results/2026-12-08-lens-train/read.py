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
    """One set's read of the shipped file S against the candidate (``MODELS``' second)."""
    c = MODELS[1]
    d = {m: load(m, name) for m in MODELS}
    assert (d["S"]["index"] == d[c]["index"]).all() and (d["S"]["label"] == d[c]["label"]).all()
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
    only_c = int((rej[c] & ~rej["S"] & (y == 0)).sum())
    only_s = int((rej["S"] & ~rej[c] & (y == 0)).sum())
    res[f"good_only_{c}"], res["good_only_S"], res["good_sign_p"] = only_c, only_s, sign_test(only_c, only_s)
    res["caught_diff_se"] = boot_se(rej[c][y == 1].astype(float), rej["S"][y == 1].astype(float))
    return res


def main(out_name: str = "read.json") -> None:
    """Print the tables and the plan's bars (the sets ``SETS`` names: B, V, N in that order); write ``out_name``."""
    c = MODELS[1]
    out: dict = {}
    print(f"| set | good | S: good rejected | {c}: good rejected | only {c} / only S (p) | S: caught | {c}: caught | "
          f"{c} - S (SE) | S: AUROC | {c}: AUROC |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for name, label in SETS.items():
        if not all((HERE / "eval" / f"{m}-{name}" / "scores.csv").exists() for m in MODELS):
            print(f"| {label} | not evaluated |||||||||")
            continue
        r = out[name] = read(name)
        s, lo = r["S"], r[c]
        print(f"| {label} | {r['good']} | {s['good_rejected']} ({s['good_rejected'] / r['good']:.1%}) | "
              f"{lo['good_rejected']} ({lo['good_rejected'] / r['good']:.1%}) | {r[f'good_only_{c}']} / "
              f"{r['good_only_S']} ({r['good_sign_p']:.2g}) | {s['caught']:.1%} | {lo['caught']:.1%} | "
              f"{lo['caught'] - s['caught']:+.1%} ({r['caught_diff_se']:.1%}) | {s['auroc']:.3f} | {lo['auroc']:.3f} |")
    for name, r in out.items():
        print(f"\n== {SETS[name]}: caught at the stored threshold / image AUROC per type")
        print(f"| type | S caught | {c} caught | S AUROC | {c} AUROC |\n|---|---|---|---|---|")
        for t in r["S"]["caught_by_type"]:
            print(f"| {t} | {r['S']['caught_by_type'][t]:.1%} | {r[c]['caught_by_type'][t]:.1%} | "
                  f"{r['S']['auroc_by_type'][t]:.3f} | {r[c]['auroc_by_type'][t]:.3f} |")
        print()
        d = {m: load(m, name) for m in MODELS}
        matched(d["S"]["score"], d[c]["score"], d["S"]["label"] == 1, ("S", c))
    bars = {}
    if set(SETS) <= out.keys():
        b, v, n = (out[k] for k in SETS)
        bars = {f"1 V: {c} good rejected <= 2.1 %": v[c]["good_rejected"] / v["good"] <= PROMISE,
                f"2 B: {c} matched mean >= S's - 1 point": b[c]["matched_mean"] >= b["S"]["matched_mean"] - 0.01,
                f"3 B: {c} good rejected <= 2.1 %": b[c]["good_rejected"] / b["good"] <= PROMISE,
                f"4 N: {c} matched mean >= S's - 2 points": n[c]["matched_mean"] >= n["S"]["matched_mean"] - 0.02}
        print("\n== the plan's bars")
        for k, ok in bars.items():
            print(f"- {k}: {'holds' if ok else 'FAILS'}")
    (HERE / out_name).write_text(json.dumps({"sets": out, "bars": bars}, indent=1))


if __name__ == "__main__":
    main()
