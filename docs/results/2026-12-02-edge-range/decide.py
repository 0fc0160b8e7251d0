"""Rule 67's decision (plan.md), from four `station eval` folders of the same 400 parts:

    python decide.py F63-S E63-S F63-E3 E63-E3 --ta 0.9785 --tb runs/c86/E63.json

A is the shipped file (F63) at threshold --ta, B the candidate (E63) at --tb (a number or a sidecar with
"threshold"). S is the line as built, E3 the same parts with 0.3 mm edges. Prints each file's figures on each set,
the paired differences with bootstrap SEs over parts (2000 resamples, seed 0), and the rule's three conditions.
``--also R3 A B`` reports another pair of the same parts (no condition), beside S without the defect types that
set leaves out (``S-as-R3``).
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


def figures(label, score, t):
    good, bad = label == 0, label == 1
    return {"good_rejected": int((score[good] > t).sum()), "good": int(good.sum()),
            "caught": float((score[bad] > t).mean()), "auroc": rank_auroc(label, score)}


def main() -> None:
    p = argparse.ArgumentParser()
    p.add_argument("a_s"), p.add_argument("b_s"), p.add_argument("a_e3"), p.add_argument("b_e3")
    p.add_argument("--ta", type=threshold, required=True)
    p.add_argument("--tb", type=threshold, required=True)
    p.add_argument("--also", nargs=3, metavar=("NAME", "A", "B"), help="another set of the same parts, reported")
    p.add_argument("--out", help="write the figures as JSON here")
    args = p.parse_args()
    rng = np.random.default_rng(0)
    out = {}
    sets = [("S", args.a_s, args.b_s, None), ("E3", args.a_e3, args.b_e3, None)]
    if args.also:
        name, fa, fb = args.also
        kinds = {k for _, k, _ in read(fa).values() if k}
        sets += [(f"S-as-{name}", args.a_s, args.b_s, kinds), (name, fa, fb, None)]
    for name, fa, fb, kinds in sets:
        a, b = read(fa), read(fb)
        idx = sorted(i for i in set(a) & set(b) if kinds is None or a[i][0] == 0 or a[i][1] in kinds)
        assert all(a[i][0] == b[i][0] for i in idx), f"{name}: labels differ"
        label = np.array([a[i][0] for i in idx])
        kind = np.array([a[i][1] for i in idx])
        sa, sb = np.array([a[i][2] for i in idx]), np.array([b[i][2] for i in idx])
        fa_, fb_ = figures(label, sa, args.ta), figures(label, sb, args.tb)
        boot = {"caught": [], "good_share": [], "auroc": []}
        for _ in range(2000):
            k = rng.integers(0, len(idx), len(idx))
            la, xa, xb = label[k], sa[k], sb[k]
            if la.min() == la.max():
                continue
            ga, gb = figures(la, xa, args.ta), figures(la, xb, args.tb)
            boot["caught"].append(gb["caught"] - ga["caught"])
            boot["good_share"].append(gb["good_rejected"] / gb["good"] - ga["good_rejected"] / ga["good"])
            boot["auroc"].append(gb["auroc"] - ga["auroc"])
        se = {k: float(np.std(v)) for k, v in boot.items()}
        types = {t: (float((sa[kind == t] > args.ta).mean()), float((sb[kind == t] > args.tb).mean()),
                     int((kind == t).sum())) for t in sorted(set(kind[label == 1]))}
        out[name] = {"A": fa_, "B": fb_, "se_of_B_minus_A": se, "caught_by_type": types}
        print(f"== {name}: {len(idx)} parts ({fa_['good']} good)")
        for who, f, t in (("A", fa_, args.ta), ("B", fb_, args.tb)):
            print(f"  {who} at {t:.4f}: good rejected {f['good_rejected']} of {f['good']} "
                  f"({100 * f['good_rejected'] / f['good']:.1f} %), caught {100 * f['caught']:.1f} %, "
                  f"image AUROC {f['auroc']:.3f}")
        print(f"  B - A: caught {100 * (fb_['caught'] - fa_['caught']):+.1f} points (SE {100 * se['caught']:.1f}), "
              f"AUROC {fb_['auroc'] - fa_['auroc']:+.3f} (SE {se['auroc']:.3f})")
        for t, (ca, cb, n) in types.items():
            print(f"    {t:13s} {n:3d}: A {100 * ca:5.1f} %  B {100 * cb:5.1f} %")
    s, e = out["S"], out["E3"]
    share = lambda f: f["good_rejected"] / f["good"]  # noqa: E731
    conditions = {
        "1 S: B caught >= A - 2 points, AUROC >= A - 0.01":
            s["B"]["caught"] >= s["A"]["caught"] - 0.02 and s["B"]["auroc"] >= s["A"]["auroc"] - 0.01,
        "2 S: B good rejected <= A + 2 points": share(s["B"]) <= share(s["A"]) + 0.02,
        "3 E3: B AUROC > S - 0.03, good rejected <= 2 x S + 2 points":
            e["B"]["auroc"] > s["B"]["auroc"] - 0.03 and share(e["B"]) <= 2 * share(s["B"]) + 0.02,
    }
    for c, ok in conditions.items():
        print(f"{'PASS' if ok else 'FAIL'}  {c}")
    print("E63 replaces the shipped file" if all(conditions.values()) else "the shipped file stays")
    out["conditions"] = conditions
    if args.out:
        Path(args.out).write_text(json.dumps(out, indent=1) + "\n")


if __name__ == "__main__":
    main()
