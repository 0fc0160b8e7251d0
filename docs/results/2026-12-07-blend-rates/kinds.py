"""After plan 2's read, from the same cached arrays (no set scored again): C and D at their own validation thresholds,
per defect kind. Run from the repository's root with PYTHONPATH=.; writes kinds.txt's lines to stdout."""
import sys

sys.path.insert(0, "docs/results/2026-12-07-ggx-train")
from screen import Decisions, arrays  # the ggx screen's per-part arrays and decisions

f = Decisions("model/weights/default")
for s in ("data/square-1238:test", "data/rough-1239:test"):
    a = arrays("model/weights/default", s)
    lab, kind = a["label"], a["kind"]
    for name, score in (("C", f.cascade(a)), ("D", f.blend(a))):
        rej = score > f.thresholds[name]
        print(s, name, ", ".join(f"{t} {int(rej[lab & (kind == t)].sum())}/{int((lab & (kind == t)).sum())}"
                                 for t in sorted(set(kind[lab]))))
