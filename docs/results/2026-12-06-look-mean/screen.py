"""plan.md's screen (validation, and two sets the shipped file read before): the cascade's gate lowered, and the
weights of the mean. Writes screen.txt's lines to stdout. Run from the repository's root after arrays.py."""
from functools import partial

import numpy as np
from decide import VAL, cascade, larger, load, mean, thresholds

from model.draem.metrics import false_reject_threshold

SETS = {"validation (selection)": VAL, "seed 1194 (used)": load("line-panel-heldout-1194_test"),
        "seed 1195, new kinds (used)": load("new-kinds-heldout-1195_test")}
good = ~VAL["label"]
decisions = {f"cascade, gate at the window's {r:.0%}": partial(cascade, gate=false_reject_threshold(
    VAL["window_sd"][good], r)) for r in (0.05, 0.10, 0.2, 0.5)}
decisions |= {"larger of the two on every part": larger}
decisions |= {f"mean, window weight {w}": partial(mean, weight=w) for w in (0.0, 0.25, 0.5, 0.75)}
for name, a in SETS.items():
    lab, kind = a["label"], a["kind"]
    print(f"\n{name}: {(~lab).sum()} good, {lab.sum()} defective")
    for d, f in decisions.items():
        t1, t5 = thresholds(f)
        s = f(a)
        per = " ".join(f"{k} {np.mean(s[lab & (kind == k)] > t1):.2f}" for k in sorted(set(kind[lab])))
        print(f"  {d:36s} caught at 1 % {np.mean(s[lab] > t1):6.1%}, at 5 % {np.mean(s[lab] > t5):6.1%}; good "
              f"rejected {np.sum(s[~lab] > t1)}; {per}")
