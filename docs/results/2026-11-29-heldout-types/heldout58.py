"""The held-out-types table (2026-11-29-heldout-types.md): for each defect type T, T's row in the report of the
network trained without T (eval-H-T) beside T's row in the shipped file's report on the same set (its network saw
T), and the whole set's row of each. Usage: python heldout58.py SHIPPED_EVAL HELDOUT_DIR (the eval-H-T folders)"""

from __future__ import annotations

import json
import sys
from pathlib import Path

TYPES = ("chip", "dent", "missing_stud", "scratch", "stain")


def rows(d: Path) -> dict[str, dict]:
    return {r["type"]: r for r in json.loads((d / "eval.json").read_text())["industrial"]}


def cell(r: dict) -> str:
    return (f"{r['image_auroc']:.3f} / {100 * r['caught_at_1%_false_rejects']:.0f} % / "
            f"{100 * r['caught_at_5%_false_rejects']:.0f} %")


def main(shipped: str, folder: str) -> None:
    x = rows(Path(shipped))
    print("| type | defective | the shipped file (saw T) | trained without T | held-out target (>= 0.85) | "
          "whole set, without T |\n|---|---|---|---|---|---|")
    for t in TYPES:
        d = Path(folder) / f"eval-H-{t}"
        if not (d / "eval.json").exists():
            print(f"| {t} | {x[t]['parts']} | {cell(x[t])} | not measured | | |")
            continue
        h = rows(d)
        assert h[t]["in_training"] == "held out", (t, h[t]["in_training"])
        met = "met" if h[t]["image_auroc"] >= 0.85 else "not met"
        print(f"| {t} | {h[t]['parts']} | {cell(x[t])} | {cell(h[t])} | {met} | {cell(h['all'])} |")
    print(f"\nEach cell: image AUROC against all good parts / caught at 1 % / caught at 5 % (thresholds from the good "
          f"validation parts). The shipped file's whole set: {cell(x['all'])}.")


if __name__ == "__main__":
    main(*sys.argv[1:3])
