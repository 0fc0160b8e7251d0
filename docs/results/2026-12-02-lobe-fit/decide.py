"""Rule 69's decision (plan.md), from `station eval` folders of the same 400 parts rendered three ways:

    python decide.py --set S E63-S L63-S --set G E63-G L63-G --set R E63-R L63-R \
        --ta model/weights/default.json --tb runs/c88/L63.json

A is the shipped file (E63) at threshold --ta, B the candidate (L63) at --tb (a number or a sidecar with
"threshold"). S is the line as built, G the same parts with a GGX lobe, R with a duller plastic. Prints each file's
figures on each set, the paired differences with bootstrap SEs over parts (2000 resamples, seed 0), caught per type,
and the rule's three conditions.
"""
import argparse
import csv
import json
from pathlib import Path

import numpy as np

from model.draem.metrics import rank_auroc


def read(folder: str) -> dict[int, tuple[int, str, float]]:
    rows = csv.DictReader(open(Path(folder) / "scores.csv"))
    return {int(r["index"]): (int(r["label"]), r["defect_type"], float(r["score"])) for r in rows}


def threshold(value: str) -> float:
    return float(json.load(open(value))["threshold"]) if value.endswith(".json") else float(value)


def figures(label: np.ndarray, score: np.ndarray, t: float) -> dict:
    good, bad = label == 0, label == 1
    return {"good_rejected": int((score[good] > t).sum()), "good": int(good.sum()),
            "caught": float((score[bad] > t).mean()), "auroc": rank_auroc(label, score)}


def share(f: dict) -> float:
    return f["good_rejected"] / f["good"]


def compare(fa: str, fb: str, ta: float, tb: float, rng: np.random.Generator) -> dict:
    a, b = read(fa), read(fb)
    idx = sorted(set(a) & set(b))
    assert all(a[i][0] == b[i][0] for i in idx), f"{fa}, {fb}: labels differ"
    label = np.array([a[i][0] for i in idx])
    kind = np.array([a[i][1] for i in idx])
    sa, sb = np.array([a[i][2] for i in idx]), np.array([b[i][2] for i in idx])
    boot: dict[str, list[float]] = {"caught": [], "good_share": [], "auroc": []}
    for _ in range(2000):
        k = rng.integers(0, len(idx), len(idx))
        if label[k].min() == label[k].max():
            continue
        ga, gb = figures(label[k], sa[k], ta), figures(label[k], sb[k], tb)
        boot["caught"].append(gb["caught"] - ga["caught"])
        boot["good_share"].append(share(gb) - share(ga))
        boot["auroc"].append(gb["auroc"] - ga["auroc"])
    types = {t: (float((sa[kind == t] > ta).mean()), float((sb[kind == t] > tb).mean()), int((kind == t).sum()))
             for t in sorted(set(kind[label == 1]))}
    return {"A": figures(label, sa, ta), "B": figures(label, sb, tb),
            "se_of_B_minus_A": {k: float(np.std(v)) for k, v in boot.items()}, "caught_by_type": types}


def main() -> None:
    p = argparse.ArgumentParser()
    p.add_argument("--set", nargs=3, action="append", metavar=("NAME", "A", "B"), required=True)
    p.add_argument("--ta", type=threshold, required=True)
    p.add_argument("--tb", type=threshold, required=True)
    p.add_argument("--out", help="write the figures as JSON here")
    args = p.parse_args()
    rng = np.random.default_rng(0)
    out = {name: compare(fa, fb, args.ta, args.tb, rng) for name, fa, fb in args.set}
    for name, r in out.items():
        print(f"== {name}: {r['A']['good']} good parts")
        for who, t in (("A", args.ta), ("B", args.tb)):
            f = r[who]
            print(f"  {who} at {t:.4f}: good rejected {f['good_rejected']} of {f['good']} ({100 * share(f):.1f} %), "
                  f"caught {100 * f['caught']:.1f} %, image AUROC {f['auroc']:.3f}")
        se, d = r["se_of_B_minus_A"], r["B"]["caught"] - r["A"]["caught"]
        print(f"  B - A: caught {100 * d:+.1f} points (SE {100 * se['caught']:.1f}), "
              f"good rejected {100 * (share(r['B']) - share(r['A'])):+.1f} points (SE {100 * se['good_share']:.1f}), "
              f"AUROC {r['B']['auroc'] - r['A']['auroc']:+.3f} (SE {se['auroc']:.3f})")
        for t, (ca, cb, n) in r["caught_by_type"].items():
            print(f"    {t:13s} {n:3d}: A {100 * ca:5.1f} %  B {100 * cb:5.1f} %")
    s = out["S"]
    conditions = {
        "1 S: B caught >= A - 2 points, AUROC >= A - 0.01":
            s["B"]["caught"] >= s["A"]["caught"] - 0.02 and s["B"]["auroc"] >= s["A"]["auroc"] - 0.01,
        "2 S: B good rejected <= A + 2 points": share(s["B"]) <= share(s["A"]) + 0.02,
        "3 G and R: B good rejected <= 3.2 %": all(share(out[n]["B"]) <= 0.032 for n in ("G", "R")),
    }
    for c, ok in conditions.items():
        print(f"{'PASS' if ok else 'FAIL'}  {c}")
    print("L63 replaces the shipped file" if all(conditions.values()) else "the shipped file stays")
    out["conditions"] = conditions
    if args.out:
        Path(args.out).write_text(json.dumps(out, indent=1) + "\n")


if __name__ == "__main__":
    main()
