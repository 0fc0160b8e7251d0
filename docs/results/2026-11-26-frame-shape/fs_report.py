"""Rule 22 (rule.md): image AUROC, good parts rejected and defects caught per scored set, with the thresholds for
1 % and 5 % of good parts rejected set on the validation set's good parts (frame_shape.py's scores).

Usage: fs_report.py OUT.json VAL_SCORES.json SCORES.json ..."""
import json
import sys

import numpy as np
from sklearn.metrics import roc_auc_score

from model.draem.metrics import false_reject_threshold

val = json.load(open(sys.argv[2]))["val"]
vs, vl = np.array(val["score"]), np.array(val["label"])
t1, t5 = (false_reject_threshold(vs[vl == 0], r) for r in (0.01, 0.05))
rows = {}
for path in sys.argv[3:]:
    for name, d in json.load(open(path)).items():
        s, lab, typ = np.array(d["score"]), np.array(d["label"]), np.array(d["type"])
        good, bad = s[lab == 0], s[lab == 1]
        r = {"parts": len(s), "good": int((lab == 0).sum()), "auroc": roc_auc_score(lab, s),
             "good_rejected_1": float((good > t1).mean()), "good_rejected_5": float((good > t5).mean()),
             "caught_1": float((bad > t1).mean()), "caught_5": float((bad > t5).mean()),
             "good_median": float(np.median(good)), "scale_median": float(np.median(d["scale"])),
             "per_type": {t: roc_auc_score(np.r_[np.zeros(len(good)), np.ones((typ == t).sum())],
                                           np.r_[good, s[typ == t]]) for t in sorted(set(typ) - {""})}}
        rows[name] = r
        print(name, {k: (round(v, 3) if isinstance(v, float) else v) for k, v in r.items() if k != "per_type"},
              {t: round(v, 3) for t, v in r["per_type"].items()})
print("thresholds from validation (variation score):", round(t1, 3), round(t5, 3))
json.dump({"thresholds": [t1, t5], "sets": rows}, open(sys.argv[1], "w"), indent=1)
