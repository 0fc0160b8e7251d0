"""The shipped model on the parts of a set that stand on a matte belt, with thresholds set on the validation set's
good parts on a matte belt: what a line with a matte belt would measure, without fitting again.
Usage: .venv/bin/python docs/results/2026-11-27-good-tail/matte_line.py runs/tail/eval-val data/line-panel-val \
    EVAL DATA [EVAL DATA ...]   (station eval folders of held-out sets and the sets they scored)"""

from __future__ import annotations

import sys

import numpy as np
from good_tail import scenes  # same folder

from model.draem.metrics import auroc, false_reject_threshold


def main() -> None:
    val = [p for p in scenes(*sys.argv[1:3]) if p["label"] == 0]
    cuts = {}
    for name, keep in (("all belts", lambda p: True), ("matte belt", lambda p: not p["glossy_belt"])):
        good = np.array([p["score"] for p in val if keep(p)])
        cuts[name] = {q: false_reject_threshold(good, q) for q in (0.01, 0.05)}  # station eval's rule
    print("| set | belts | good | defective | image AUROC | 1 % threshold: caught (good rejected) | "
          "5 % threshold: caught (good rejected) |\n|---|---|---|---|---|---|---|")
    args = sys.argv[3:]
    for ev, data in zip(args[::2], args[1::2], strict=True):
        parts = scenes(ev, data)
        for name, keep in (("all belts", lambda p: True), ("matte belt", lambda p: not p["glossy_belt"])):
            sub = [p for p in parts if keep(p)]
            good = np.array([p["score"] for p in sub if p["label"] == 0])
            bad = np.array([p["score"] for p in sub if p["label"] == 1])
            cells = [f"{100 * np.mean(bad > cuts[name][q]):.0f} % ({100 * np.mean(good > cuts[name][q]):.1f} %)"
                     for q in (0.01, 0.05)]
            a = auroc(np.r_[np.ones(len(bad)), np.zeros(len(good))], np.r_[bad, good])
            print(f"| {data} | {name} | {len(good)} | {len(bad)} | {a:.3f} | {cells[0]} | {cells[1]} |")


if __name__ == "__main__":
    main()
