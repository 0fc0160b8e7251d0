"""station bench shift of S and C on seed 1240 as built (plan.md), side by side: good parts rejected at each file's
stored threshold (of the set's 146 good parts) and image AUROC, per shift; the intensity-only files read no DoLP or
AoLP, so those shifts are left out.

    python docs/results/2026-12-07-blend-otherwise/shift_table.py > .../shift.txt
"""
import json
from pathlib import Path

HERE = Path(__file__).parent
rows = {m: {r["shift"]: r for r in json.loads((HERE / f"shift-{m}" / "shift.json").read_text())["rows"]}
        for m in ("S", "C")}
good = json.loads((HERE / "shift-S" / "shift.json").read_text())["good_parts"]
print("| shift | S: good rejected | C: good rejected | S: caught at the 1 % threshold | C | S: image AUROC | C |")
print("|---|---|---|---|---|---|---|")
for name, s in rows["S"].items():
    if name.startswith(("dolp", "aolp")):
        continue
    c = rows["C"][name]
    print(f"| {name} | {round(s['good_rejected_own'] * good)} | {round(c['good_rejected_own'] * good)} | "
          f"{s['caught_1%']:.1%} | {c['caught_1%']:.1%} | {s['image_auroc']:.3f} | {c['image_auroc']:.3f} |")
