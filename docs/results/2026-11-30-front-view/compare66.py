"""Check 66 (plan.md): the line camera's file and the second camera's file F on the same parts of seed 1167.

Usage (repository root):
    python docs/results/2026-11-30-front-view/compare66.py LINE_EVAL LINE_DATA F_EVAL LINE_VAL_EVAL F_VAL_EVAL [SEED]
LINE_EVAL, F_EVAL: `station eval` reports on seed SEED (default 1167) from each camera; LINE_DATA: the line camera's
set (its ground-truth normals give each defect's face); *_VAL_EVAL: each file's report on its validation set
(`--split val`; the twins of one set: the same parts). Prints the plan's tables in Markdown.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "2026-11-27-bright-field"))
from faces import faces_of

from model.draem.metrics import false_reject_threshold, paired_auroc_gains
from station.eval_compare import read_report, read_scores

RATE = 0.01
"""The issue's rate of good parts rejected."""


def aligned(a: dict, b: dict) -> tuple[list[int], np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """(indices, truth, types, a's scores, b's scores) on the parts both reports hold. A part is defective when
    either camera sees its defect (its label in either set); its type from whichever does."""
    idx = sorted(set(a) & set(b))
    assert len(idx) == len(a) == len(b), "the reports are not on the same parts"
    y = np.array([a[i][0] or b[i][0] for i in idx], bool)
    t = np.array([a[i][1] or b[i][1] for i in idx])
    return idx, y, t, np.array([a[i][2] for i in idx]), np.array([b[i][2] for i in idx])


def caught_row(name: str, y: np.ndarray, t: np.ndarray, rejected: np.ndarray) -> str:
    types = sorted(set(t[y]))
    per = " | ".join(f"{rejected[y & (t == k)].mean():.0%}" for k in types)
    return (f"| {name} | {int(rejected[~y].sum())} of {int((~y).sum())} ({rejected[~y].mean():.1%}) | "
            f"{int(rejected[y].sum())} of {int(y.sum())} ({rejected[y].mean():.1%}) | {per} |")


def paired_caught(y: np.ndarray, base: np.ndarray, other: np.ndarray) -> tuple[float, float]:
    """Points caught, other minus base, over the defective parts, and its standard error (paired)."""
    d = other[y].astype(float) - base[y].astype(float)
    return 100 * d.mean(), 100 * d.std(ddof=1) / np.sqrt(d.size)


def combined_score(line: np.ndarray, second: np.ndarray, t_line: float, t_second: float) -> np.ndarray:
    """The combined rule's score (check 66's plan): each file's score over its own threshold, the larger of the two.
    The rule thresholds it at ``RATE`` of the good validation parts' combined scores."""
    return np.maximum(line / t_line, second / t_second)


def faces(line_eval: str, line_data: str, idx: list[int], y: np.ndarray) -> np.ndarray:
    """Each part's face by the line camera's ground-truth normals ("" for good parts; "unseen by the line camera"
    for a defect only the second camera sees)."""
    _, groups = faces_of(line_eval, line_data)
    return np.array([groups[i][1] if i in groups else ("unseen by the line camera" if y[k] else "")
                     for k, i in enumerate(idx)])


def print_by_face(face: np.ndarray, y: np.ndarray, rows: dict[str, np.ndarray], header: str) -> None:
    """The share of each face's defective parts each rule rejects, a Markdown table under ``header``'s columns."""
    print("\nBy face (the line camera's ground truth), caught:\n")
    print(f"| face | defective | {header} |\n|---|---|" + "---|" * len(rows))
    for f in sorted(set(face[y])):
        m = y & (face == f)
        print(f"| {f} | {int(m.sum())} | " + " | ".join(f"{rows[k][m].mean():.0%}" for k in rows) + " |")


def main() -> None:
    line_eval, line_data, f_eval, line_val, f_val = sys.argv[1:6]
    seed = sys.argv[6] if len(sys.argv) > 6 else "1167"
    tl, tf = (float(read_report(d)["threshold"]) for d in (line_eval, f_eval))
    line = read_scores(line_eval)
    idx, y, t, sl, sf = aligned(line, read_scores(f_eval))
    seen_line = np.array([line[i][0] == 1 for i in idx])
    face = faces(line_eval, line_data, idx, y)
    vidx, vy, _, vl, vf = aligned(read_scores(line_val), read_scores(f_val))
    tc = false_reject_threshold(combined_score(vl, vf, tl, tf)[~vy], RATE)
    comb = combined_score(sl, sf, tl, tf)
    print(f"Seed {seed}: {len(idx)} parts, {int((~y).sum())} good, {int(y.sum())} defective "
          f"({int((y & ~seen_line).sum())} of them seen by the second camera only). Thresholds: line {tl:.4f}, "
          f"F {tf:.4f}; combined {tc:.4f} (1 % of the {int((~vy).sum())} good validation parts, "
          f"{len(vidx)} parts).\n")
    types = sorted(set(t[y]))
    print("| rule | good parts rejected | defective parts caught | " + " | ".join(types) + " |")
    print("|---|---|---|" + "---|" * len(types))
    rows = {"line camera alone (the shipped file)": sl > tl, "second camera alone (F)": sf > tf,
            "either camera rejects": (sl > tl) | (sf > tf), "combined at 1 %": comb > tc}
    for name, rej in rows.items():
        print(caught_row(name, y, t, rej))
    print()
    for name in ("either camera rejects", "combined at 1 %"):
        g, se = paired_caught(y, rows["line camera alone (the shipped file)"], rows[name])
        print(f"- {name}, caught minus the line camera alone: {g:+.1f} points (paired SE {se:.1f})")
    print_by_face(face, y, rows, "line camera | F | either | combined at 1 %")
    print("\nImage AUROC by face and type (each group's defective parts against all good parts), F against the line "
          "camera, paired bootstrap:\n")
    print("| group | defective | line camera | F | F - line (SE) | combined | combined - line (SE) |")
    print("|---|---|---|---|---|---|---|")
    groups_ft = np.where(y, np.char.add(np.char.add(face, ": "), t), "")
    for key, labels in (("face", np.where(y, face, "")), ("type", np.where(y, t, "")), ("face and type", groups_ft)):
        rf = {r["type"]: r for r in paired_auroc_gains(y, labels, sl, sf)}
        rc = {r["type"]: r for r in paired_auroc_gains(y, labels, sl, comb)}
        for g in rf:
            if key != "face" and g == "all":
                continue
            a, c = rf[g], rc[g]
            print(f"| {g} | {a['defective']} | {a['base']:.3f} | {a['other']:.3f} | {a['gain']:+.3f} ({a['se']:.3f}) | "
                  f"{c['other']:.3f} | {c['gain']:+.3f} ({c['se']:.3f}) |")
    missed = y & (sl <= tl)
    print(f"\nOf the line camera's {int(missed.sum())} misses, F catches {int((missed & (sf > tf)).sum())} at its own "
          f"threshold, the combined rule {int((missed & (comb > tc)).sum())}:\n")
    print("| face: type | missed by the line camera | caught by F | caught combined |\n|---|---|---|---|")
    for g in sorted(set(groups_ft[missed])):
        m = missed & (groups_ft == g)
        print(f"| {g} | {int(m.sum())} | {int((m & (sf > tf)).sum())} | {int((m & (comb > tc)).sum())} |")


if __name__ == "__main__":
    main()
