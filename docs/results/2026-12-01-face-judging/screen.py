"""The face-judging screen (plan.md): the shipped variation model's window maps on data/line-pv-val, their maximum
over every judged pixel (A) and off the front face (B), caught at 1 % of the good parts per face of the defect.

    python screen.py > screen.md   (from the repository root; about 5 min on 2 cores)
    python screen.py runs/make-side-model/side data/sw-pv-val 0,0,1 only > screen-side.md   (the side camera: its
        front face, seen square, the only one judged under B)
"""
import json
import sys

import numpy as np
import torch

from model.draem.checkpoint import load_checkpoint
from model.draem.metrics import false_reject_threshold
from model.draem.preprocess import crop_resize
from model.draem.roi import roi_box
from sim.dataset import open_dataset
from sim.defects import defect_face
from station.evaluation import model_split

MODEL, DATA = (sys.argv[1], sys.argv[2]) if len(sys.argv) > 2 else ("model/weights/default", "data/line-pv-val")
# the front face's normal as the camera sees it (camera coordinates; the line camera's by default)
FRONT = np.array([float(v) for v in sys.argv[3].split(",")]) if len(sys.argv) > 3 else np.array([0.0, -0.53, 0.84])
ONLY = len(sys.argv) > 4 and sys.argv[4] == "only"  # B judges the front face only (else everything but it)
COS = np.cos(np.radians(25.0))

ck = load_checkpoint(MODEL)
cfg, var = ck.detector.config, ck.detector.variation
sp = model_split(ck, MODEL, DATA, "val")
ds = open_dataset(DATA)
front_masks = []
for i in sp.index:  # each part's front face at the model input, as its defect mask is cropped and resized
    s = ds.load(i)
    front = (s.normal @ FRONT > COS) & s.object_mask
    box = roi_box(cfg.roi, s.object_mask.shape, s.object_mask, cfg.frame_aspect)
    _, (fm,) = crop_resize(np.zeros((1, *front.shape), np.float32), box, cfg.input_shape, ("intensity",), (front,))
    front_masks.append(fm)
reg = var.register_masks(sp.priors, torch.stack(front_masks)).numpy()  # in the reference's pixels
y = sp.label.numpy().astype(bool)
front_ref = reg[~y].mean(0) > 0.5  # most good parts' front face
out = var.zmaps(sp.priors)
maps = out.maps.numpy()
a = maps.reshape(len(maps), -1).max(1)
b = np.where(front_ref != ONLY, 0.0, maps).reshape(len(maps), -1).max(1)
faces = [defect_face(json.load(open(f"{DATA}/samples/{i:06d}/params.json")).get("defect")) if y[k] else ""
         for k, i in enumerate(sp.index)]
ta, tb = false_reject_threshold(a[~y], 0.01), false_reject_threshold(b[~y], 0.01)
print(f"{MODEL} on {DATA}: B judges {'only' if ONLY else 'all but'} the front face.\n")
print(f"{int((~y).sum())} good, {int(y.sum())} defective; front face: {front_ref.mean():.1%} of the reference "
      f"frame; 1 % points A {ta:.3f}, B {tb:.3f}\n")
print("| defects on | n | caught A | caught B | B - A (paired SE) |\n|---|---|---|---|---|")
for name, sel in [("all", y), *[(f or "unknown", y & (np.array(faces) == f)) for f in
                                 ("top", "front", "end", "edge", None)]]:
    if name == "unknown":
        sel = y & np.array([f is None for f in faces])
    if not sel.any():
        continue
    ca, cb = a[sel] > ta, b[sel] > tb
    d = cb.astype(float) - ca
    se = d.std(ddof=1) / np.sqrt(d.size) if d.size > 1 else float("nan")
    print(f"| {name} | {int(sel.sum())} | {int(ca.sum())} | {int(cb.sum())} | {d.mean():+.3f} ({se:.3f}) |")
top_good = np.argsort(-np.where(y, -np.inf, a))[:10]
on_front = [bool(front_ref.reshape(-1)[maps[k].reshape(-1).argmax()]) for k in top_good]
print(f"\nThe 10 highest good parts under A: maxima on the front face in {sum(on_front)} "
      f"(scores {np.round(a[top_good], 2).tolist()}).", file=sys.stdout)
np.savez_compressed("/tmp/face_screen.npz", a=a, b=b, y=y, front_ref=front_ref)
