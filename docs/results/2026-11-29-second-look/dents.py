"""Where the second look loses dents and scratches (used sets only, nothing chosen): for each defective part of a
held-out set, its window score (robust SD over the good validation parts), whether it is above the gate, which of
the shipped proposals first touches its registered mask (0: none), the test score of that region and the part's
best test score, both in robust SD as the shipped second look puts them. Usage: PYTHONPATH=. python dents.py SET..."""

from __future__ import annotations

import copy
import sys

import numpy as np

from model.draem.checkpoint import load_checkpoint
from model.draem.second_look import proposals
from station.evaluation import model_split

MODEL = "model/weights/default"
ck = load_checkpoint(MODEL)
vm = copy.deepcopy(ck.detector.variation)
look = vm.second_look
gate, wl, ws, tl, ts = (float(v) for v in look.calibration)
look.calibration[0] = np.inf
part = vm.region.numpy()
rows = []
for root in sys.argv[1:]:
    sp = model_split(ck, MODEL, root, "test")
    bad = np.flatnonzero(sp.label.numpy() == 1)
    for i in range(0, len(bad), 50):
        b = bad[i:i + 50]
        x = sp.priors[b].float()
        o = vm.zmaps(x, signed=True)
        masks = vm.register_masks(x, sp.defect_mask[b].bool()).numpy()
        for k, (m, s, j, mk) in enumerate(zip(o.maps.numpy(), o.signed.numpy(), o.judged.numpy(), masks,
                                              strict=True)):
            chi = (s.astype(np.float32) ** 2).sum(0)
            w = (float(m.max()) - wl) / ws
            first, t_at, best = 0, -np.inf, -np.inf
            for r, reg in enumerate(proposals(m), 1):
                t = (look.test(m * reg, chi, j, part) - tl) / ts
                best = max(best, t)
                if not first and (reg & mk).any():
                    first, t_at = r, t
            rows.append((sp.defect_type[b[k]], w, w > gate, first, t_at, best, int((mk & j).sum()), int(mk.sum())))
thr1 = 16.12  # the shipped cascade's 1 % threshold on the good validation parts, robust SD (analyze.py)
print(f"{len(rows)} defective parts; gate {gate:.2f}, 1 % threshold {thr1}")
print("| type | parts | above gate | a proposal touches it | its region's test > 1 % thr | caught at 1 % | "
      "mask judged (median share) |")
print("|---|---|---|---|---|---|---|")
for ty in sorted({r[0] for r in rows}):
    rr = [r for r in rows if r[0] == ty]
    n = len(rr)
    g = [r for r in rr if r[2]]
    touch = [r for r in g if r[3]]
    hit = [r for r in touch if r[4] > thr1]
    caught = [r for r in rr if max(r[1], r[5] if r[2] else -np.inf) > thr1]
    share = np.median([r[6] / max(r[7], 1) for r in rr])
    print(f"| {ty} | {n} | {len(g) / n:.0%} | {len(touch) / n:.0%} | {len(hit) / n:.0%} | {len(caught) / n:.0%} | "
          f"{share:.0%} |")
d = [r for r in rows if r[0] == "dent" and r[2]]
print("\ndents above the gate, proposal rank that touches (0 none):", np.bincount([r[3] for r in d], minlength=6))
print("their window / touching region's test (robust SD), sorted by window:")
for r in sorted(d, key=lambda r: -r[1]):
    print(f"  {r[1]:6.1f} {r[4]:7.1f} rank {r[3]}  mask {r[7]} px, judged {r[6]}")
