"""How much of each rendered defect the shipped variation model judges (highlights are not judged, by design): per
type, the defects whose registered mask is mostly (> 50 %) in a hidden highlight, and whether the model caught them at
the validation 1 % threshold. Usage: PYTHONPATH=. python hidden.py DATA THRESHOLD (from the repository root)."""

from __future__ import annotations

import sys

import numpy as np

from model.draem.checkpoint import load_checkpoint
from station.evaluation import model_split

MODEL = "model/weights/default"
data, threshold = sys.argv[1], float(sys.argv[2])
ck = load_checkpoint(MODEL)
vm = ck.detector.variation
sp = model_split(ck, MODEL, data, "test")
bad = np.flatnonzero(sp.label.numpy() == 1)
x = sp.priors[bad].float()
reg = vm.register_masks(x, sp.defect_mask[bad].bool()).numpy()
out = [vm.zmaps(x[i:i + 50], signed=True) for i in range(0, len(x), 50)]
judged = np.concatenate([o.judged.numpy() for o in out])
caught = ck.detector.predict(x).score.numpy() > threshold
types = np.array([sp.defect_type[i] for i in bad])
share = np.array([(r & j).sum() / max(r.sum(), 1) for r, j in zip(reg, judged, strict=True)])
print("| type | defects | mostly in a highlight | of those caught at 1 % |\n|---|---|---|---|")
for t in ["all", *sorted(set(types))]:
    sel = np.ones(len(types), bool) if t == "all" else types == t
    hid = sel & (share < 0.5)
    print(f"| {t} | {sel.sum()} | {hid.sum()} | {caught[hid].sum()} |")
