"""Check 64c (plan-64c.md): the shipped file on seed 1167 without stray light, paired with check 64's report.

Usage (repository root): python docs/results/2026-11-30-report-1167/score64c.py
Reads data/line-panel-heldout-1167-B, data/twins-1168-B (the shielded line's good parts, for its threshold) and
runs/c64/eval/scores.csv (seed 1167 as built, `station eval` of the shipped file: run.sh).
"""

from __future__ import annotations

import numpy as np
import torch

from model.draem.checkpoint import load_checkpoint
from model.draem.metrics import false_reject_threshold, paired_auroc_gains
from station.eval_compare import read_scores
from station.evaluation import model_split

MODEL = "model/weights/default"
SHIELDED = "data/line-panel-heldout-1167-B"
SHIELDED_GOOD = "data/twins-1168-B"
AS_BUILT = "runs/c64/eval"
RATE = 0.01


@torch.no_grad()
def decision_scores(ck, data: str, good_only: bool = False) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """(dataset indices, labels, defect types, the shipped file's decision scores) of the set's test split."""
    sp = model_split(ck, MODEL, data, "test", good_only=good_only)
    det = ck.detector.eval()
    s = np.concatenate([det.predict(sp.priors[i:i + 16], None).score.float().numpy()
                        for i in range(0, len(sp.label), 16)])
    return np.array(sp.index), sp.label.numpy().astype(bool), np.array(sp.defect_type), s


def row(name: str, y: np.ndarray, t: np.ndarray, s: np.ndarray, thr: float) -> str:
    types = sorted(set(t[y]))
    per = " | ".join(f"{np.mean(s[y & (t == k)] > thr):.0%}" for k in types)
    return (f"| {name} | {thr:.4f} | {int((s[~y] > thr).sum())} of {int((~y).sum())} ({np.mean(s[~y] > thr):.1%}) | "
            f"{int((s[y] > thr).sum())} of {int(y.sum())} ({np.mean(s[y] > thr):.1%}) | {per} |")


def paired_table(y: np.ndarray, t: np.ndarray, a: np.ndarray, b: np.ndarray, base: str, other: str,
                 change: str) -> None:
    """Print image AUROC of scores ``a`` and ``b`` on the same parts, in all and per type, with the paired change."""
    print(f"\n| type | defective | image AUROC, {base} | {other} | {change} (paired SE) |\n|---|---|---|---|---|")
    for r in paired_auroc_gains(y, np.where(y, t, ""), a, b):
        print(f"| {r['type']} | {r['defective']} | {r['base']:.3f} | {r['other']:.3f} | {r['gain']:+.3f} "
              f"({r['se']:.3f}) |")


def main() -> None:
    ck = load_checkpoint(MODEL)
    own = float(ck.meta["threshold"])
    _, _, _, good = decision_scores(ck, SHIELDED_GOOD, good_only=True)
    shielded_thr = false_reject_threshold(good, RATE)
    idx, y, t, b = decision_scores(ck, SHIELDED)
    base = read_scores(AS_BUILT)
    assert all(base[i][:2] == (int(yi), ti) for i, yi, ti in zip(idx, y, t, strict=True)), "not the same parts"
    a = np.array([base[i][2] for i in idx])
    types = sorted(set(t[y]))
    print(f"Seed 1167, {len(idx)} parts ({int((~y).sum())} good, {int(y.sum())} defective), the same parts as built "
          f"and shielded; the shielded line's 1 % threshold from {len(good)} good parts of {SHIELDED_GOOD}.\n")
    print("| set | threshold | good parts rejected | defective parts caught | " + " | ".join(types) + " |")
    print("|---|---|---|---|" + "---|" * len(types))
    print(row("as built, own threshold (check 64)", y, t, a, own))
    print(row("shielded, own threshold", y, t, b, own))
    print(row("shielded, shielded line's 1 % threshold", y, t, b, shielded_thr))
    paired_table(y, t, a, b, "as built", "shielded", "change")


if __name__ == "__main__":
    main()
