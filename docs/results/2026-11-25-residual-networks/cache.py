"""Cache the shipped variation model's signed per-channel residual z maps (refit on TRAIN's good parts), and the
fit's mean, channel scale and per-pixel scale (read by docs/results/2026-11-25-physical-anomalies/)."""

from __future__ import annotations

import copy
import sys

import numpy as np
from spies import JUD, RES, install

from model.draem.checkpoint import load_checkpoint
from model.draem.variation import FOLDS
from station.datasets import load_split

PRIORS = ("intensity", "dolp", "aolp")
SHAPE = (96, 192)
install()


def load(root, split, good_only=False):
    s = load_split(root, split, PRIORS, SHAPE, roi="band", progress=False, good_only=good_only)
    return s


train_dir, val_dir, held_dir, out = sys.argv[1:5]
st = load(train_dir, "train", good_only=True)
xt = st.priors.float()
n = len(xt)
shipped = load_checkpoint("model/weights/default").detector.variation
m = copy.deepcopy(shipped)
RES.clear()
JUD.clear()
m.fit(xt, st.object_mask)
resid = np.empty((n, *RES[0].shape[1:]), np.float32)
for f in range(FOLDS):
    resid[np.arange(n) % FOLDS == f] = RES[f]
scale = m.scale.numpy()
ztrain = m.used(np.moveaxis(resid / scale, 1, 0))
ztrain = np.moveaxis(ztrain, 0, 1)
print("train", ztrain.shape, flush=True)
d = {
    "train_z": ztrain.astype(np.float16),
    "region": m.region.numpy(),
    "location": m.window_location.numpy(),
    "spread": m.window_spread.numpy(),
    "mean": m.mean.numpy(),
    "channel_scale": m.channel_scale.numpy(),
    "scale": m.scale.numpy(),
}
for tag, root, split in (("val", val_dir, "val"), ("held", held_dir, "test")):
    s = load(root, split)
    x = s.priors.float()
    RES.clear()
    JUD.clear()
    scores = np.concatenate([m.zmaps(x[i : i + 50]).scores.numpy() for i in range(0, len(x), 50)])
    z = np.stack([m.used(r[0] / scale) for r in RES])
    d[f"{tag}_z"] = z.astype(np.float16)
    d[f"{tag}_judged"] = np.stack(JUD)
    d[f"{tag}_label"] = s.label.numpy()
    d[f"{tag}_type"] = np.array([t or "" for t in s.defect_type])
    d[f"{tag}_score"] = scores
    d[f"{tag}_mask"] = s.defect_mask.numpy().astype(bool) if s.defect_mask is not None else np.zeros(1)
    print(tag, z.shape, flush=True)
np.savez(out, **d)
