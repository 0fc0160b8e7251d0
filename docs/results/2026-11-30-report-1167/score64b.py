"""Check 64b (plan-64b.md): the shipped file's scores on twin sets of the same good parts, paired by index.

Usage (repository root): python docs/results/2026-11-30-report-1167/score64b.py SET_A SET_B [SET_C ...]
The first set is the reference (the line as built); each other set is compared with it part by part.
"""

from __future__ import annotations

import sys

import numpy as np
import torch

from model.draem.checkpoint import load_checkpoint
from station.evaluation import model_split

MODEL = "model/weights/default"
TOP = 0.10
"""The paired change is read on the reference set's top TOP of good parts by variation score (plan-64b.md)."""


@torch.no_grad()
def scores(ck, data: str) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(dataset indices, decision scores, variation scores) of the set's good test parts."""
    sp = model_split(ck, MODEL, data, "test", good_only=True)
    det = ck.detector.eval()
    dec, var = [], []
    for i in range(0, len(sp.label), 16):
        out = det.predict(sp.priors[i:i + 16], None)
        dec.append(out.score.float().numpy())
        var.append(out.member_scores["variation"].float().numpy())
    return np.array(sp.index), np.concatenate(dec), np.concatenate(var)


def main() -> None:
    sets = sys.argv[1:]
    ck = load_checkpoint(MODEL)
    thr = float(ck.meta["threshold"])
    got = {s: scores(ck, s) for s in sets}
    ref_idx, _, ref_var = got[sets[0]]
    print(f"Shipped file {MODEL}, threshold {thr}; good parts of each set (the same seed's parts).\n")
    print("| set | good parts | above the threshold | variation score: median | 90th | 99th | max |")
    print("|---|---|---|---|---|---|---|")
    for s, (idx, dec, var) in got.items():
        q = np.percentile(var, [50, 90, 99])
        above = int((dec > thr).sum())
        print(f"| {s} | {len(idx)} | {above} ({above / len(idx):.1%}) | {q[0]:.2f} | {q[1]:.2f} | {q[2]:.2f} | "
              f"{var.max():.2f} |")
    top = np.argsort(-ref_var)[: max(1, round(TOP * len(ref_var)))]
    print(f"\nPaired with {sets[0]} (same indices): each part's variation score ratio, other / reference.\n")
    print("| set | parts paired | median ratio, all | median ratio, reference's top 10 % | parts "
          "| top 10 % lower by >= 20 % (median) |")
    print("|---|---|---|---|---|---|")
    for s in sets[1:]:
        idx, _, var = got[s]
        assert np.array_equal(idx, ref_idx), f"{s}: not the same parts as {sets[0]}"
        r = var / np.maximum(ref_var, 1e-6)
        rt = np.median(r[top])
        print(f"| {s} | {len(idx)} | {np.median(r):.3f} | {rt:.3f} | {len(top)} | {'yes' if rt <= 0.8 else 'no'} |")


if __name__ == "__main__":
    main()
