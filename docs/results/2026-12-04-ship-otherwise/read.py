"""The plan's reads (plan.md): the shipped intensity-only file S against E63 on seed 1196 as built, shaped, moving
and sensed otherwise.

    PYTHONPATH=. .venv/bin/python docs/results/2026-12-04-ship-otherwise/read.py > .../read.txt

Each file at its stored threshold (a part is rejected when its score is above it). Writes read.json beside it.
"""
import csv
import json
from math import comb
from pathlib import Path

import numpy as np

from model.draem.metrics import auroc

HERE = Path(__file__).parent
SETS = {"built": "as built", "chamfer03": "edges chamfered 0.3 mm", "round03": "edges rounded 0.3 mm (no chips)",
        "motion2": "moving 2 px in the exposure", "motion4": "moving 4 px in the exposure",
        "pedestal256": "black level 256 codes, unstated", "camera": "polarizer, gain spread and pedestal 64",
        "hot30": "30 pixels stuck at full scale, unmapped", "blurff": "a lens blur of 0.7 px (addendum)",
        "allff": "that blur, vignetting and three sensor imperfections (addendum)"}
MODELS = ("S", "E63")
TYPES = ("chip", "dent", "missing_stud", "scratch", "stain")


def load(model: str, name: str) -> dict:
    folder = HERE / "eval" / f"{model}-{name}"
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


def read(name: str) -> dict:
    d = {m: load(m, name) for m in MODELS}
    assert (d["S"]["index"] == d["E63"]["index"]).all() and (d["S"]["label"] == d["E63"]["label"]).all()
    y, types = d["S"]["label"], d["S"]["type"]
    rej = {m: d[m]["score"] > d[m]["threshold"] for m in MODELS}
    res: dict = {"good": int((y == 0).sum()), "defective": int((y == 1).sum())}
    for m in MODELS:
        s = d[m]["score"]
        res[m] = {"good_rejected": int(rej[m][y == 0].sum()), "caught": float(rej[m][y == 1].mean()),
                  "caught_no_chips": float(rej[m][(y == 1) & (types != "chip")].mean()),
                  "auroc": auroc(y, s),
                  "caught_by_type": {t: float(rej[m][types == t].mean()) for t in TYPES if (types == t).any()},
                  "auroc_by_type": {t: auroc(y[(y == 0) | (types == t)], s[(y == 0) | (types == t)])
                                    for t in TYPES if (types == t).any()}}
    only_s = int((rej["S"] & ~rej["E63"] & (y == 0)).sum())
    only_e = int((rej["E63"] & ~rej["S"] & (y == 0)).sum())
    res["good_only_S"], res["good_only_E63"], res["good_sign_p"] = only_s, only_e, sign_test(only_s, only_e)
    res["caught_diff_se"] = boot_se(rej["S"][y == 1].astype(float), rej["E63"][y == 1].astype(float))
    return res


def bars(out: dict) -> None:
    """The plan's bar per rendering, printed and stored."""
    for name, r in out.items():
        if name == "built" or "S" not in r:
            continue
        n, s, e = r["good"], r["S"], r["E63"]
        own = out["built"]["S"]["caught_no_chips" if name == "round03" else "caught"]
        bar1 = s["good_rejected"] / n <= max(0.03, e["good_rejected"] / n + 0.013)
        bar2 = s["caught"] >= own - 0.05 and s["caught"] >= e["caught"] - 0.05
        r["bar_good"], r["bar_caught"] = bool(bar1), bool(bar2)
        print(f"{name}: bar 1 (good rejected) {'holds' if bar1 else 'FAILS'}; "
              f"bar 2 (caught vs own as built {own:.1%} and E63) {'holds' if bar2 else 'FAILS'}")


def stated() -> dict | None:
    """After the reads (not in the plan): S on the pedestal set with its black level stated in the set's manifest,
    as `[camera] black_level` states it to the station, against S on the set as built (the same parts)."""
    if not (HERE / "eval" / "S-pedestal256bl" / "scores.csv").exists():
        return None
    built, bl = load("S", "built"), load("S", "pedestal256bl")
    assert (built["index"] == bl["index"]).all()
    y = built["label"]
    res = {}
    for name, d in (("built", built), ("pedestal256bl", bl)):
        rej = d["score"] > d["threshold"]
        res[name] = {"good_rejected": int(rej[y == 0].sum()), "caught": float(rej[y == 1].mean()),
                     "auroc": auroc(y, d["score"])}
    print(f"S, black level 256 stated: {res['pedestal256bl']['good_rejected']} of {int((y == 0).sum())} good parts "
          f"rejected, {res['pedestal256bl']['caught']:.1%} caught, image AUROC {res['pedestal256bl']['auroc']:.3f} "
          f"(as built: {res['built']['good_rejected']}, {res['built']['caught']:.1%}, {res['built']['auroc']:.3f})")
    return res


def main() -> None:
    out: dict = {}
    print("| rendering | good | S: good rejected | E63: good rejected | only S / only E63 (p) | S: caught | "
          "E63: caught | S - E63 (SE) | S: AUROC | E63: AUROC |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for name, label in SETS.items():
        if not all((HERE / "eval" / f"{m}-{name}" / "scores.csv").exists() for m in MODELS):
            print(f"| {label} | not evaluated |||||||||")
            continue
        r = out[name] = read(name)
        s, e = r["S"], r["E63"]
        print(f"| {label} | {r['good']} | {s['good_rejected']} ({s['good_rejected'] / r['good']:.1%}) | "
              f"{e['good_rejected']} ({e['good_rejected'] / r['good']:.1%}) | {r['good_only_S']} / "
              f"{r['good_only_E63']} ({r['good_sign_p']:.2g}) | {s['caught']:.1%} | {e['caught']:.1%} | "
              f"{s['caught'] - e['caught']:+.1%} ({r['caught_diff_se']:.1%}) | {s['auroc']:.3f} | {e['auroc']:.3f} |")
    print()
    print("| rendering | file | " + " | ".join(TYPES) + " |")
    print("|---|---|" + "---|" * len(TYPES))
    for name, r in out.items():
        for m in MODELS:
            cells = [f"{r[m]['caught_by_type'][t]:.0%} ({r[m]['auroc_by_type'][t]:.3f})"
                     if t in r[m]["caught_by_type"] else "" for t in TYPES]
            print(f"| {SETS[name]} | {m} | " + " | ".join(cells) + " |")
    print("\ncells: caught at the file's threshold (image AUROC against the rendering's good parts)\n")
    if "built" in out:
        bars(out)
    if (res := stated()) is not None:
        out["pedestal256_stated"] = res
    (HERE / "read.json").write_text(json.dumps(out, indent=1))


if __name__ == "__main__":
    main()
