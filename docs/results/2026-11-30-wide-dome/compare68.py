"""Check 68 (plan.md): the side camera's file under the narrow dome (O) and under the wide one (W), each beside the
line camera's file, on the same parts of seed 1169.

Usage (repository root):
    python docs/results/2026-11-30-wide-dome/compare68.py LINE_EVAL LINE_DATA O_EVAL W_EVAL LINE_VAL O_VAL W_VAL
*_EVAL: `station eval` reports on seed 1169; LINE_DATA: the line camera's set (its ground-truth normals give each
defect's face); *_VAL: each file's report on its validation set (`--split val`; twins: the same parts). Prints the
plan's tables in Markdown.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "2026-11-30-front-view"))
from compare66 import RATE, aligned, caught_row, combined_score, faces, paired_caught, print_by_face

from model.draem.metrics import false_reject_threshold, paired_auroc_gains
from station.eval_compare import read_report, read_scores


def main() -> None:
    line_eval, line_data, o_eval, w_eval, line_val, o_val, w_val = sys.argv[1:8]
    tl, to, tw = (float(read_report(d)["threshold"]) for d in (line_eval, o_eval, w_eval))
    line = read_scores(line_eval)
    idx, y, t, sl, so = aligned(line, read_scores(o_eval))
    idx_w, y_w, _, _, sw = aligned(line, read_scores(w_eval))
    assert idx_w == idx and (y_w == y).all(), "the two domes' reports are not on the same parts and truths"
    face = faces(line_eval, line_data, idx, y)
    vl_all = read_scores(line_val)
    combined, tails = {}, {}
    for name, val, ts, s in (("O", o_val, to, so), ("W", w_val, tw, sw)):
        _, vy, _, vl, vs = aligned(vl_all, read_scores(val))
        tc = false_reject_threshold(combined_score(vl, vs, tl, ts)[~vy], RATE)
        combined[name] = combined_score(sl, s, tl, ts) > tc
        tails[name] = (ts, np.sort(vs[~vy])[-5:][::-1], int((~vy).sum()))
    print(f"Seed 1169: {len(idx)} parts, {int((~y).sum())} good, {int(y.sum())} defective. Thresholds: line "
          f"{tl:.4f}, O {to:.4f}, W {tw:.4f}.\n")
    print("Good validation tail (each file on its own dome's validation twin):\n")
    print("| file | threshold | good validation parts | five highest good scores |\n|---|---|---|---|")
    for name, (ts, top, n) in tails.items():
        print(f"| {name} | {ts:.4f} | {n} | {', '.join(f'{v:.4f}' for v in top)} |")
    types = sorted(set(t[y]))
    print("\n| rule | good parts rejected | defective parts caught | " + " | ".join(types) + " |")
    print("|---|---|---|" + "---|" * len(types))
    rows = {"line camera alone": sl > tl, "O alone (dome 0.22 m)": so > to, "W alone (dome 0.36 m)": sw > tw,
            "either camera, O": (sl > tl) | (so > to), "either camera, W": (sl > tl) | (sw > tw),
            "combined at 1 %, O": combined["O"], "combined at 1 %, W": combined["W"]}
    for name, rej in rows.items():
        print(caught_row(name, y, t, rej))
    print()
    for a, b in (("either camera, O", "either camera, W"), ("O alone (dome 0.22 m)", "W alone (dome 0.36 m)"),
                 ("line camera alone", "either camera, W"), ("line camera alone", "combined at 1 %, W"),
                 ("combined at 1 %, O", "combined at 1 %, W")):
        g, se = paired_caught(y, rows[a], rows[b])
        print(f"- {b} minus {a}: {g:+.1f} points caught (paired SE {se:.1f})")
    print_by_face(face, y, rows, " | ".join(rows))
    print("\nImage AUROC of the side camera's file, W against O, by face and type (each group's defective parts "
          "against all good parts), paired bootstrap:\n")
    print("| group | defective | O | W | W - O (SE) |\n|---|---|---|---|---|")
    groups_ft = np.where(y, np.char.add(np.char.add(face, ": "), t), "")
    for key, labels in (("face", np.where(y, face, "")), ("face and type", groups_ft)):
        for r in paired_auroc_gains(y, labels, so, sw):
            if key != "face" and r["type"] == "all":
                continue
            print(f"| {r['type']} | {r['defective']} | {r['base']:.3f} | {r['other']:.3f} | {r['gain']:+.3f} "
                  f"({r['se']:.3f}) |")


if __name__ == "__main__":
    main()
