"""After the read (no decision; every set here is used): the good parts each decision alone rejects, with their window
and network findings over their own thresholds; and D kept to the parts above the cascade's gate (below it a part
passes, as in the cascade), on every set. Run from the repository's root after read.py; writes after.txt's lines."""
from functools import partial

import numpy as np
from decide import GATE, T_F, T_W, VAL, cascade, load, mean, thresholds

SETS = ["look-built-1222_test", "look-new-kinds-1223_test", "look-ggx-1224_test", "look-rough-1224_test"]


def gated(a: dict[str, np.ndarray], weight: float = 0.25) -> np.ndarray:
    """D above the gate; 0 (a pass) below it."""
    return np.where(a["window_sd"] > GATE, mean(a, weight), 0.0)


(c1, _), (d1, _) = thresholds(cascade), thresholds(mean)
print("good parts rejected by one decision only (window / t_w, network / t_f):")
for name in SETS:
    a = load(name)
    good = np.flatnonzero(~a["label"])
    c, d = cascade(a)[good] > c1, mean(a)[good] > d1
    for tag, only in (("C only", c & ~d), ("D only", d & ~c)):
        parts = ", ".join(f"{i} ({a['score'][i] / T_W:.2f} / {a['found'][i] / T_F:.2f})" for i in good[only])
        print(f"  {name}: {tag}: {parts or '-'}")
print("\nD above the gate only (weight 0.25 and 0), caught at 1 % and 5 %, good parts rejected at 1 %:")
for w in (0.25, 0.0):
    f = partial(gated, weight=w)
    t1, t5 = thresholds(f)
    for name, a in [("validation", VAL), *((n, load(n)) for n in SETS)]:
        lab, s = a["label"], f(a)
        print(f"  weight {w}: {name:26s} {np.mean(s[lab] > t1):6.1%} {np.mean(s[lab] > t5):6.1%}  "
              f"{np.sum(s[~lab] > t1)} of {(~lab).sum()}")
