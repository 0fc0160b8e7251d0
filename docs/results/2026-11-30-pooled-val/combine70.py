"""Check 70 (plan.md): the line camera's file and the side camera's WS on the same parts, thresholds from two
validation twins pooled (seeds 303 and 304).

Rules, all at the 1 % budget of the pooled good validation parts (floor of 1 % of them):
- line camera alone: its threshold at 1 % of the pooled good validation parts (the baseline of the plan's bar);
- line camera alone at the shipped file's own threshold (from seed 303's validation only), reported;
- split: check 68's rule on the pooled validation scores (``model.draem.camera_split.split_thresholds``, which gives
  ``combine68.choose_split``'s rows; this script called the latter when check 70 was read, with the same output);
- either camera, each at 1 % of its pooled good validation parts (a 2 % rule by design), reported.
A frame either camera's station would not judge (`station eval`'s ``unjudged``, with that camera's presence rule)
is rejected by every rule that reads that camera.

Usage (repository root):
    python docs/results/2026-11-30-pooled-val/combine70.py LINE_VAL,LINE_VAL SIDE_VAL,SIDE_VAL \
        [LINE_EVAL SIDE_EVAL LINE_DATA SEED]
*_VAL: each file's `station eval --split val` reports on the validation twins, in the same order for both cameras;
*_EVAL: reports on a held-out seed (the same parts); LINE_DATA: the line camera's held-out set (faces from its
ground-truth normals). Validation only when the held-out reports are not given. Prints Markdown.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "2026-11-30-front-view"))
from compare66 import RATE, aligned, caught_row, faces, paired_caught, print_by_face

from model.draem.camera_split import split_rejects, split_thresholds
from model.draem.metrics import false_reject_threshold
from station.eval_compare import read_report, read_scores


def unjudged(folder: str, idx: list[int]) -> np.ndarray:
    """Whether each part's frame is one the camera's station would not judge (eval.json's ``unjudged``; reports
    from before 2026-11-30 do not list them)."""
    left = json.loads((Path(folder) / "eval.json").read_text()).get("unjudged", {})
    return np.array([str(i) in left for i in idx], bool)


def pooled(line_vals: list[str], side_vals: list[str]) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(defective, line scores, side scores) over every validation twin, concatenated; a part either camera's
    station would not judge is left out, as `station threshold` leaves it out."""
    parts = []
    for a, b in zip(line_vals, side_vals, strict=True):
        idx, y, _, sl, ss = aligned(read_scores(a), read_scores(b))
        keep = ~(unjudged(a, idx) | unjudged(b, idx))
        parts.append((y[keep], sl[keep], ss[keep]))
    return tuple(np.concatenate([p[k] for p in parts]) for k in range(3))


def main() -> None:
    line_vals, side_vals = sys.argv[1].split(","), sys.argv[2].split(",")
    vy, vl, vs = pooled(line_vals, side_vals)
    budget = int(np.floor(RATE * (~vy).sum()))
    rows, best = split_thresholds(vy, vl, vs, RATE)
    t_line, t_side = (false_reject_threshold(v[~vy], RATE) for v in (vl, vs))
    print(f"Pooled validation ({len(line_vals)} twins): {vy.size} parts, {int((~vy).sum())} good (budget {budget} "
          f"good parts), {int(vy.sum())} defective. Each camera alone at 1 %: line {t_line:.4f}, side "
          f"{t_side:.4f}.\n")
    print("| side camera's good parts above a_s (k) | a_l | a_s | defective caught (validation) |\n|---|---|---|---|")
    for i, r in enumerate(rows):
        print(f"| {r.k}{' (chosen)' if i == best else ''} | {r.first:.4f} | {r.second:.4f} | {r.caught:.1%} |")
    line_alone = vl > t_line
    print(f"\nLine camera alone at 1 % on validation: {line_alone[vy].mean():.1%} of defective parts, "
          f"{int(line_alone[~vy].sum())} good parts.")
    if len(sys.argv) < 7:
        return
    line_eval, side_eval, line_data, seed = sys.argv[3:7]
    idx, y, t, sl, ss = aligned(read_scores(line_eval), read_scores(side_eval))
    ul, us = unjudged(line_eval, idx), unjudged(side_eval, idx)
    shipped = float(read_report(line_eval)["threshold"])
    split = rows[best]
    line_rej = (sl > t_line) | ul
    rules = {"line camera alone (pooled 1 %)": line_rej,
             "line camera alone (the shipped threshold)": (sl > shipped) | ul,
             "side camera alone (pooled 1 %)": (ss > t_side) | us,
             "either camera (each pooled 1 %)": line_rej | (ss > t_side) | us,
             "split at 1 % (chosen on validation)": split_rejects(sl, ss, split) | ul | us}
    print(f"\nSeed {seed}: {len(idx)} parts, {int((~y).sum())} good, {int(y.sum())} defective; frames not judged: "
          f"line {int(ul.sum())}, side {int(us.sum())}. Thresholds: line {t_line:.4f} (shipped {shipped:.4f}), side "
          f"{t_side:.4f}; split a_l {split.first:.4f}, a_s {split.second:.4f}.\n")
    types = sorted(set(t[y]))
    print("| rule | good parts rejected | defective parts caught | " + " | ".join(types) + " |")
    print("|---|---|---|" + "---|" * len(types))
    for name, rej in rules.items():
        print(caught_row(name, y, t, rej))
    print()
    for name in ("either camera (each pooled 1 %)", "split at 1 % (chosen on validation)"):
        g, se = paired_caught(y, line_rej, rules[name])
        print(f"- {name} minus the line camera alone (pooled 1 %): {g:+.1f} points caught (paired SE {se:.1f})")
    face = faces(line_eval, line_data, idx, y)
    print_by_face(face, y, rules, " | ".join(rules))


if __name__ == "__main__":
    main()
