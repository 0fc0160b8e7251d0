"""What the second look raises among good parts (validation only, nothing chosen): each good validation part above
the gate, its window and test scores in robust SD, and for its highest-testing region (each region tested alone:
the map kept only there, proposed again) the place (row, column of the 96 x 192 input), its size and how near full
scale the frame's I (1 + DoLP) comes within 5 px of it (highlights are not judged; 1.0 is full scale).
Usage: PYTHONPATH=. python tail.py (from the repository root)."""

import cv2
import numpy as np

from model.draem.checkpoint import load_checkpoint
from model.draem.second_look import proposals
from station.evaluation import model_split

M = "model/weights/default"
ck = load_checkpoint(M)
vm = ck.detector.variation
look = vm.second_look
gate, wl, ws, tl, ts = (float(v) for v in look.calibration)
sp = model_split(ck, M, "data/line-panel-val", "val")
good = np.flatnonzero(sp.label.numpy() == 0)
x = sp.priors[good].float()
rows = []
for i in range(0, len(x), 50):
    o = vm.zmaps(x[i:i + 50], signed=True)
    for k, (m, s, j) in enumerate(zip(o.maps.numpy(), o.signed.numpy(), o.judged.numpy(), strict=True)):
        w = float(m.max())
        if (w - wl) / ws <= gate:
            continue
        xi = x[i + k].numpy()
        peak = vm.register(xi, vm.features(xi))[-1]
        best, where = -np.inf, None
        for reg in proposals(m):
            t = look.test(m * reg, (s ** 2).sum(0), j, vm.region.numpy())
            if t > best:
                best, where = t, reg
        near = cv2.dilate(where.astype(np.uint8), np.ones((11, 11), np.uint8)).astype(bool)
        yy, xx = np.nonzero(where)
        rows.append((sp.index[good[i + k]], (w - wl) / ws, (best - tl) / ts, int(yy.mean()), int(xx.mean()),
                     int(where.sum()), float(peak[near].max())))
rows.sort(key=lambda r: -max(r[1], r[2]))
print(f"{len(rows)} good validation parts above the gate ({gate:.2f} robust SD)")
print("part  window  test  row  col  region_px  peak_near")
for r in rows:
    print(f"{r[0]:4d}  {r[1]:6.1f}  {r[2]:5.1f}  {r[3]:3d}  {r[4]:3d}  {r[5]:9d}  {r[6]:.2f}")
