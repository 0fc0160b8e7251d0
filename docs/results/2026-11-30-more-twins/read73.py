"""Check 73's reading (plan.md): the two cameras at the pooled split (seeds 303 + 1176) against rule 64's split
(seed 303 alone, split-b1.json) and the line camera alone, on seeds 1174, 1175 and 1177, per seed and pooled.
A frame a camera would not judge is rejected by every rule that reads it (as station compare --split does).

    python docs/results/2026-11-30-more-twins/read73.py > docs/results/2026-11-30-more-twins/read73.md
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from model.draem.camera_split import SplitThresholds, split_rejects
from model.draem.rate_bounds import interval
from station.eval_compare import read_report, read_scores

HERE = Path(__file__).parent
SPLITS = {"rule 64 (seed 303)": HERE.parent / "2026-11-30-threshold-counts" / "split-b1.json",
          "pooled (303 + 1176)": HERE / "split-pooled.json"}
SEEDS = (1174, 1175, 1177)


def decisions(seed: int) -> dict:
    line, side = f"runs/check-{seed}/eval-line", f"runs/check-{seed}/eval-side"
    a, b = read_scores(line), read_scores(side)
    idx = sorted(a)
    assert idx == sorted(b)
    y = np.array([bool(a[i][0] or b[i][0]) for i in idx])
    types = np.array([a[i][1] or b[i][1] for i in idx])
    sa, sb = (np.array([s[i][2] for i in idx]) for s in (a, b))
    left = [np.array([str(i) in read_report(f).get("unjudged", {}) for i in idx]) for f in (line, side)]
    rules = {"line camera alone": (sa > float(read_report(line)["threshold"])) | left[0]}
    for name, path in SPLITS.items():
        s = json.loads(path.read_text())
        pair = SplitThresholds(**s["splits"][s["chosen"]])
        rules[f"both, {name} ({pair.first:.4f}, {pair.second:.4f})"] = split_rejects(sa, sb, pair) | left[0] | left[1]
    return {"y": y, "types": types, "rules": rules}


def row(label: str, y: np.ndarray, types: np.ndarray, rules: dict) -> list[str]:
    base, b1 = list(rules.values())[:2]
    out = []
    for name, r in rules.items():
        k, n = int(r[~y].sum()), int((~y).sum())
        lo, hi = interval(k, n)
        gains = []
        for ref in (base, b1):
            d = r[y].astype(float) - ref[y].astype(float)
            gains.append(f"{100 * d.mean():+.1f} ({100 * d.std(ddof=1) / np.sqrt(d.size):.1f})")
        per = " / ".join(f"{t} {r[y & (types == t)].mean():.0%}" for t in sorted(set(types[y])))
        out.append(f"| {label} | {name} | {k} of {n} ({100 * k / n:.2f} %; {100 * lo:.1f}-{100 * hi:.1f} %) | "
                   f"{int(r[y].sum())} of {int(y.sum())} ({100 * r[y].mean():.1f} %) | {gains[0]} | {gains[1]} | "
                   f"{per} |")
    return out


def main() -> None:
    got = {s: decisions(s) for s in SEEDS}
    print("| seed | rule | good parts rejected (exact 95 % interval) | defective caught | minus line alone, points "
          "(paired SE) | minus rule 64's split | per type |")
    print("|---|---|---|---|---|---|---|")
    for s, g in got.items():
        print("\n".join(row(str(s), g["y"], g["types"], g["rules"])))
    y = np.concatenate([g["y"] for g in got.values()])
    types = np.concatenate([g["types"] for g in got.values()])
    names = list(got[SEEDS[0]]["rules"])
    rules = {n: np.concatenate([list(g["rules"].values())[k] for g in got.values()]) for k, n in enumerate(names)}
    print("\n".join(row("all three", y, types, rules)))


if __name__ == "__main__":
    main()
