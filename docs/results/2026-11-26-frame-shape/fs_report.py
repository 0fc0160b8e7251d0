"""Rule 22 (rule.md): image AUROC, good parts rejected and defects caught per scored set, with the thresholds for
1 % and 5 % of good parts rejected set on the validation set's good parts and held fixed
(``model.draem.metrics.detection_by_type``, as ``station eval``), from frame_shape.py's scores.

Usage: fs_report.py OUT.json VAL_SCORES.json SCORES.json ..."""
import json
import sys

import numpy as np

from model.draem.metrics import detection_by_type

val = json.load(open(sys.argv[2]))["val"]
validation = (np.array(val["label"]), np.array(val["score"]))
rows, thresholds = {}, None
for path in sys.argv[3:]:
    for name, d in json.load(open(path)).items():
        s, lab = np.array(d["score"]), np.array(d["label"])
        rep = detection_by_type(lab, s, d["type"], validation=validation)
        thresholds = [rep.thresholds[0.01], rep.thresholds[0.05]]
        r = {"parts": len(s), "good": int((lab == 0).sum()), "auroc": rep.overall.image_auroc,
             "good_rejected_1": rep.false_reject_observed[0.01], "good_rejected_5": rep.false_reject_observed[0.05],
             "caught_1": rep.overall.caught[0.01], "caught_5": rep.overall.caught[0.05],
             "good_median": float(np.median(s[lab == 0])), "scale_median": float(np.median(d["scale"])),
             "per_type": {t: v.image_auroc for t, v in rep.per_type.items()}}
        rows[name] = r
        print(name, {k: (round(v, 3) if isinstance(v, float) else v) for k, v in r.items() if k != "per_type"},
              {t: round(v, 3) for t, v in r["per_type"].items()})
print("thresholds from validation (variation score):", [round(t, 3) for t in thresholds or []])
json.dump({"thresholds": thresholds, "sets": rows}, open(sys.argv[1], "w"), indent=1)
