"""Read a screen's scores: image AUROC and share caught at the statistic's own 1 % point on the good parts, per type
and face; then beside the shipped file's decision score on the same parts (its ``station eval`` scores.csv): the
odd good parts set each threshold, the even good parts and every defective part are scored.

    python read.py val303-A.json shipped-val303-scores.csv s5.0
"""
import csv
import json
import sys

import numpy as np
from scipy.stats import spearmanr
from sklearn.metrics import roc_auc_score

from model.draem.metrics import false_reject_threshold

GROUPS = ["all", "dent-top", "dent-other", "scratch-top", "scratch-other", "stain", "chip", "missing_stud"]


def members(rows: list[dict], group: str) -> list[dict]:
    return [r for r in rows if r["label"] and group in ("all", r["type"], f'{r["type"]}-{r["face"]}')]


def own(rows: list[dict], keys: list[str]) -> None:
    good = [r for r in rows if r["label"] == 0]
    print(f"good parts {len(good)}")
    for k in keys:
        g = [r[k] for r in good]
        t = false_reject_threshold(g, 0.01)
        cells = []
        for grp in GROUPS:
            d = [r[k] for r in members(rows, grp)]
            if d:
                auc = roc_auc_score([0] * len(g) + [1] * len(d), g + d)
                cells.append(f"{grp} ({len(d)}) {auc:.3f} / {np.mean(np.array(d) > t):.0%}")
        print(f"{k}: own 1 % point {t:.2f}\n   " + "\n   ".join(cells))


def beside(rows: list[dict], shipped_csv: str, key: str) -> None:
    ship = {f"{int(r['index']):06d}": float(r["score"]) for r in csv.DictReader(open(shipped_csv))}
    good = [r for r in rows if r["label"] == 0]
    odd, even = good[1::2], good[0::2]
    dents = members(rows, "dent-top")
    print(f"\nbeside the shipped file ({key}); Spearman on top-face dents "
          f"{spearmanr([ship[r['name']] for r in dents], [r[key] for r in dents])[0]:.2f}, on good parts "
          f"{spearmanr([ship[r['name']] for r in good], [r[key] for r in good])[0]:.2f}")
    for name, f in (("shipped", lambda r: ship[r["name"]]), ("screen", lambda r: r[key])):
        print(f"  image AUROC, top-face dents against good parts, {name}: "
              f"{roc_auc_score([0] * len(good) + [1] * len(dents), [f(r) for r in good + dents]):.3f}")
    for rate in (0.01, 0.02):
        odd_ship, odd_screen = [ship[r["name"]] for r in odd], [r[key] for r in odd]
        ts, ta = false_reject_threshold(odd_ship, rate), false_reject_threshold(odd_screen, rate)
        hs, ha = false_reject_threshold(odd_ship, rate / 2), false_reject_threshold(odd_screen, rate / 2)
        rules = {"shipped": lambda r, ts=ts: ship[r["name"]] > ts, "screen": lambda r, ta=ta: r[key] > ta,
                 "either, each at half": lambda r, hs=hs, ha=ha: ship[r["name"]] > hs or r[key] > ha,
                 "either, each at full": lambda r, ts=ts, ta=ta: ship[r["name"]] > ts or r[key] > ta}
        print(f"  at {rate:.0%} of the odd good parts:")
        for rule, f in rules.items():
            cells = [f"good (even) {np.mean([f(r) for r in even]):.1%}"]
            cells += [f"{g} {np.mean([f(r) for r in members(rows, g)]):.2f}" for g in GROUPS if members(rows, g)]
            print(f"    {rule}: " + ", ".join(cells))


if __name__ == "__main__":
    data = json.load(open(sys.argv[1]))
    own(data, [k for k in data[0] if k.startswith("s") and k != "split"])
    if len(sys.argv) > 3:
        beside(data, sys.argv[2], sys.argv[3])
