"""Check 68's second part (plan-1170.md): the line camera's file and the side camera's W on the same parts, under
three rules: either camera rejecting at its own 1 % threshold, the larger score over its threshold at 1 %
(check 67's combined rule), and a budget split chosen on validation.

The split: the line camera rejects when its score is above a_l, the side camera when its score is above a_s. On the
validation twins (the same parts from both cameras), for k = 0, 1, 2, ... up to the 1 % budget (floor of 1 % of the
good validation parts), a_s is the side camera's k-th highest good score (k = 0: above its highest), and a_l the
lowest line threshold at which the union still rejects at most the budget's good parts. The k with the most
defective validation parts caught is kept (ties: the smaller k). Nothing of it looks at the test set.

Usage (repository root):
    python docs/results/2026-11-30-wide-dome/combine68.py LINE_VAL SIDE_VAL [LINE_EVAL SIDE_EVAL LINE_DATA SEED]
*_VAL: each file's `station eval --split val` report on its validation twin; *_EVAL: reports on a held-out seed
(the same parts); LINE_DATA: the line camera's held-out set (faces from its ground-truth normals). Validation only
when the held-out reports are not given. Prints Markdown.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "2026-11-30-front-view"))
from compare66 import RATE, aligned, caught_row, combined_score, faces, paired_caught, print_by_face

from model.draem.metrics import false_reject_threshold
from station.eval_compare import read_report, read_scores


def above(scores: np.ndarray, k: int) -> float:
    """A threshold with exactly the ``k`` highest of ``scores`` above it (k = 0: the highest itself)."""
    s = np.sort(scores)[::-1]
    return float(s[k]) if k < s.size else float(s[-1]) - 1.0


def choose_split(y: np.ndarray, sl: np.ndarray, ss: np.ndarray) -> tuple[list[tuple[int, float, float, float]], int]:
    """(rows of (k, a_l, a_s, caught share), the chosen row's index) on validation scores; y: defective."""
    budget = int(np.floor(RATE * (~y).sum()))
    rows = []
    for k in range(budget + 1):
        a_s = above(ss[~y], k)
        side = ss > a_s
        rest = np.sort(sl[~y & ~side])[::-1]  # the good parts the side camera passes, line scores high first
        a_l = above(rest, budget - int(side[~y].sum()))
        rej = side | (sl > a_l)
        assert rej[~y].sum() <= budget
        rows.append((k, a_l, a_s, float(rej[y].mean())))
    best = max(range(len(rows)), key=lambda i: (rows[i][3], -i))
    return rows, best


def main() -> None:
    line_val, side_val = sys.argv[1:3]
    vidx, vy, _, vl, vs = aligned(read_scores(line_val), read_scores(side_val))
    rows, best = choose_split(vy, vl, vs)
    print(f"Validation: {len(vidx)} parts, {int((~vy).sum())} good (budget {int(np.floor(RATE * (~vy).sum()))} "
          f"good parts), {int(vy.sum())} defective.\n")
    print("| side camera's good parts above a_s (k) | a_l | a_s | defective caught (validation) |\n|---|---|---|---|")
    for i, (k, a_l, a_s, c) in enumerate(rows):
        print(f"| {k}{' (chosen)' if i == best else ''} | {a_l:.4f} | {a_s:.4f} | {c:.1%} |")
    if len(sys.argv) < 7:
        return
    line_eval, side_eval, line_data, seed = sys.argv[3:7]
    tl, ts = (float(read_report(d)["threshold"]) for d in (line_eval, side_eval))
    line = read_scores(line_eval)
    idx, y, t, sl, ss = aligned(line, read_scores(side_eval))
    tc = false_reject_threshold(combined_score(vl, vs, tl, ts)[~vy], RATE)
    _, a_l, a_s, _ = rows[best]
    rules = {"line camera alone": sl > tl, "side camera alone (W)": ss > ts, "either camera": (sl > tl) | (ss > ts),
             "combined at 1 %": combined_score(sl, ss, tl, ts) > tc, "split at 1 % (chosen on validation)":
             (sl > a_l) | (ss > a_s)}
    print(f"\nSeed {seed}: {len(idx)} parts, {int((~y).sum())} good, {int(y.sum())} defective. Thresholds: line "
          f"{tl:.4f}, W {ts:.4f}; combined {tc:.4f}; split a_l {a_l:.4f}, a_s {a_s:.4f}.\n")
    types = sorted(set(t[y]))
    print("| rule | good parts rejected | defective parts caught | " + " | ".join(types) + " |")
    print("|---|---|---|" + "---|" * len(types))
    for name, rej in rules.items():
        print(caught_row(name, y, t, rej))
    print()
    for name in ("either camera", "combined at 1 %", "split at 1 % (chosen on validation)"):
        g, se = paired_caught(y, rules["line camera alone"], rules[name])
        print(f"- {name} minus the line camera alone: {g:+.1f} points caught (paired SE {se:.1f})")
    face = faces(line_eval, line_data, idx, y)
    print_by_face(face, y, rules, " | ".join(rules))


if __name__ == "__main__":
    main()
