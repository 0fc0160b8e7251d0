"""The outline check on parts rendered otherwise (not in the plan; a robustness reading, nothing chosen on it): the
shipped file with the check (runs/outline/S) scored on the sets rule 70's shape check was read on, against that
reading's reports of the file before it (docs/results/2026-12-05-moulding-kinds/rule70/C-*, the same file as B):
good parts rejected and defective parts caught, and which decisions changed. Run from the repository's root."""

import csv
import json
from pathlib import Path

import numpy as np

from model.draem.checkpoint import load_checkpoint
from station.evaluation import model_split

RULE70 = Path("docs/results/2026-12-05-moulding-kinds/rule70")
SETS = {"1194 (as built)": ("line-panel-heldout-1194", "C-1194"), "1193 GGX": ("ir-ggx-1193", "C-ggx"),
        "1193 duller": ("ir-rough-1193", "C-rough"), "1196 chamfered 0.3": ("so-chamfer03-1196", "C-chamfer03"),
        "1196 rounded 0.3": ("so-round03-1196", "C-round03"), "1198 moulding": ("moulding-1198", "C-1198")}
ck = load_checkpoint("runs/outline/S")
det = ck.detector.eval()
for tag, (data, report) in SETS.items():
    before = {int(r["index"]): (r["label"], r["defect_type"], float(r["score"]))
              for r in csv.DictReader(open(RULE70 / report / "scores.csv"))}
    threshold = json.loads((RULE70 / report / "eval.json").read_text())["threshold"]
    sp = model_split(ck, "runs/outline/S", f"data/{data}", "test")
    keep = [i for i, idx in enumerate(sp.index) if idx in before]
    x = sp.priors[keep]
    s = np.concatenate([det.predict(x[i:i + 16]).score.float().numpy() for i in range(0, len(x), 16)])
    idx = [sp.index[i] for i in keep]
    label = np.array([before[i][0] == "1" for i in idx])
    b = np.array([before[i][2] > threshold for i in idx])
    a = s > ck.threshold
    changed = [f"{before[i][1] or 'good'} {i}" for i, c in zip(idx, a != b, strict=True) if c]
    print(f"{tag:20s} good rejected {int(b[~label].sum())} -> {int(a[~label].sum())} of {int((~label).sum())}; "
          f"defective caught {int(b[label].sum())} -> {int(a[label].sum())} of {int(label.sum())}; "
          f"decisions changed: {len(changed)} ({', '.join(changed)})", flush=True)
