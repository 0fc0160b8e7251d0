"""Rule 8 (rule.md), a probe: a network that maps the camera priors' residual to the true normals' residual, trained
without dents, and the shipped statistic over the priors' and the predicted normals' residuals.

Usage: normals.py OUT.json, from the repository root (data/line-polar-{train,val,heldout}; about 20 min on 2 cores).
Two variation models share the registration (the same reference and region: both are fitted on the same good parts,
and registration reads log intensity only): A, the shipped one refitted (the camera's priors: the network's input,
and the shipped statistic), and B, with the renderer's true normals as three more channels (training targets only;
nothing of B is used at test time)."""

from __future__ import annotations

import copy
import json
import sys
import time

import cv2
import numpy as np
import torch
import torch.nn.functional as F
from bootstrap import compare, held_out
from torch import nn

from model.draem.checkpoint import load_checkpoint
from model.draem.variation import (
    ABS_NORMAL_SD,
    MEDIAN_ABS_NORMAL,
    NOISE_CAP,
    SIGNED_CLIP,
    WINDOW_BLUR_PX,
    WINDOW_QUANTILE,
    VariationModel,
)
from station.datasets import load_split

torch.set_num_threads(2)
SHAPE, BOX, HOLDOUT = (96, 192), 5, "dent"
CAMERA = ("intensity", "dolp", "aolp")
PRIORS = (*CAMERA, "normal")
PRIOR_Z = [0, 2, 3]  # log I, S1/S0, S2/S0 of a 4-channel model (DoLP is not read: zero)
NORMAL_Z = [4, 5, 6]


def load(root, split, good_only=False):
    return load_split(root, split, PRIORS, SHAPE, roi="band", progress=False, good_only=good_only)


def signed(model, x):
    out = [model.zmaps(x[i : i + 50], signed=True) for i in range(0, len(x), 50)]
    return torch.cat([o.signed for o in out]).numpy(), torch.cat([o.judged for o in out]).numpy()


t0 = time.time()
tr = load("data/line-polar-train", "train")
lab = tr.label.numpy()
typ = np.array([t or "" for t in tr.defect_type])
good = lab == 0
x_all = tr.priors.float()
a = copy.deepcopy(load_checkpoint("model/weights/default").detector.variation)
a_good = a.fit(x_all[good][:, :4], tr.object_mask[good])[:, PRIOR_Z]
b = VariationModel(7, SHAPE, 0, 1, 2, box_px=BOX)
b_good = b.fit(x_all[good], tr.object_mask[good])[:, NORMAL_Z]
assert np.array_equal(a.region.numpy(), b.region.numpy()), "A and B must share the region"
print(f"fitted A and B on {int(good.sum())} good parts, {time.time() - t0:.0f}s", flush=True)
dsel = (lab == 1) & (typ != HOLDOUT)
a_def, j_def = signed(a, x_all[dsel][:, :4])
b_def, _ = signed(b, x_all[dsel])
region = a.region.numpy()
ls = np.log(a.window_spread.numpy())
ls = ((ls - ls[region].mean()) / ls[region].std() * region).astype(np.float32)


def inputs(z, judged):
    n = len(z)
    extra = np.broadcast_to(np.stack([region.astype(np.float32), ls]), (n, 2, *region.shape))
    return np.concatenate([z[:, PRIOR_Z] if z.shape[1] == 4 else z, extra], 1).astype(np.float32)


X = np.concatenate([inputs(a_good, np.repeat(region[None], len(a_good), 0)), inputs(a_def[:, PRIOR_Z], j_def)])
Y = np.concatenate([b_good, b_def[:, NORMAL_Z]]).astype(np.float32)
J = np.concatenate([np.repeat(region[None], len(a_good), 0), j_def & region])
n_good = len(a_good)
print(f"training on {n_good} good and {len(X) - n_good} defective parts (no {HOLDOUT}s)", flush=True)


class Net(nn.Module):
    def __init__(self, i=5, o=3, w=16):
        super().__init__()

        def blk(a, b):
            return nn.Sequential(nn.Conv2d(a, b, 3, padding=1), nn.ReLU(), nn.Conv2d(b, b, 3, padding=1), nn.ReLU())

        self.e1, self.e2, self.e3 = blk(i, w), blk(w, 2 * w), blk(2 * w, 2 * w)
        self.d2, self.d1 = blk(4 * w, 2 * w), blk(3 * w, w)
        self.out = nn.Conv2d(w, o, 1)

    def forward(self, x):
        e1 = self.e1(x)
        e2 = self.e2(F.max_pool2d(e1, 2))
        e3 = self.e3(F.max_pool2d(e2, 2))
        d2 = self.d2(torch.cat([e2, F.interpolate(e3, size=e2.shape[2:])], 1))
        return self.out(self.d1(torch.cat([e1, F.interpolate(d2, size=e1.shape[2:])], 1)))


rng = np.random.default_rng(0)
torch.manual_seed(0)
net = Net()
opt = torch.optim.Adam(net.parameters(), 1e-3)
steps = 3000
sched = torch.optim.lr_scheduler.MultiStepLR(opt, [int(steps * 0.8)], 0.2)
ch, cw = 64, 96
for step in range(steps):
    idx = np.concatenate([rng.integers(0, n_good, 12), rng.integers(n_good, len(X), 4)])
    y0, x0 = rng.integers(0, SHAPE[0] - ch + 1, 16), rng.integers(0, SHAPE[1] - cw + 1, 16)
    xb = torch.from_numpy(
        np.stack([X[i, :, a_ : a_ + ch, b_ : b_ + cw] for i, a_, b_ in zip(idx, y0, x0, strict=True)])
    )
    yb = torch.from_numpy(
        np.stack([Y[i, :, a_ : a_ + ch, b_ : b_ + cw] for i, a_, b_ in zip(idx, y0, x0, strict=True)])
    )
    jb = torch.from_numpy(np.stack([J[i, a_ : a_ + ch, b_ : b_ + cw] for i, a_, b_ in zip(idx, y0, x0, strict=True)]))
    loss = (net(xb) - yb.clamp(-SIGNED_CLIP, SIGNED_CLIP)).abs().mean(1)[jb].mean()
    opt.zero_grad()
    loss.backward()
    opt.step()
    sched.step()
    if step % 500 == 0 or step == steps - 1:
        print(f"step {step} L1 {loss.item():.3f} {time.time() - t0:.0f}s", flush=True)
net.eval()


def predict(z, judged):
    with torch.no_grad():
        return np.concatenate(
            [net(torch.from_numpy(inputs(z[i : i + 32], judged[i : i + 32]))).numpy() for i in range(0, len(z), 32)]
        )


sets = {}
for name, root, split in (("val", "data/line-polar-val", "val"), ("held", "data/line-polar-heldout", "test")):
    s = load_split(root, split, CAMERA, SHAPE, roi="band", progress=False)
    z, j = signed(a, s.priors.float())
    sets[name] = {
        "z": z[:, PRIOR_Z],
        "judged": j,
        "pred": predict(z[:, PRIOR_Z], j),
        "label": s.label.numpy(),
        "type": np.array([t or "" for t in s.defect_type]),
    }
print(f"scored, {time.time() - t0:.0f}s", flush=True)
eroded = cv2.erode(region.astype(np.uint8), np.ones((3, 3), np.uint8)).astype(bool)


def level(z, judged):
    v = float(np.median(np.abs(z[:, judged]))) / MEDIAN_ABS_NORMAL if judged.any() else 1.0
    return v if 1.0 < v <= NOISE_CAP else 1.0


def windows(zs, judged):
    return np.stack(
        [
            cv2.blur((np.abs(z) / level(z, j)).max(0), (BOX, BOX), borderType=cv2.BORDER_REPLICATE)
            for z, j in zip(zs, judged, strict=True)
        ]
    )


def calibrate(w):
    loc = np.median(w, 0)
    spread = cv2.GaussianBlur(np.percentile(w, WINDOW_QUANTILE, 0) - loc, (0, 0), WINDOW_BLUR_PX)
    return loc, np.maximum(spread, max(float(np.percentile(spread[region], 5.0)), ABS_NORMAL_SD / BOX))


def scores(w, judged, cal):
    loc, spread = cal
    return np.array(
        [
            float(np.maximum((wi - loc) / spread, 0)[eroded & j].max(initial=0.0))
            for wi, j in zip(w, judged, strict=True)
        ]
    )


v = sets["val"]
cal_parts = np.where(v["label"] == 0)[0][::2]
rest = np.setdiff1d(np.arange(len(v["label"])), cal_parts)
pscale = 1.4826 * np.median(np.abs(v["pred"][cal_parts]), 0)
pscale = np.maximum(pscale, np.array([np.percentile(p[region], 5.0) for p in pscale])[:, None, None])
shipped_cal = (a.window_location.numpy(), a.window_spread.numpy())


def both(s):
    return np.concatenate([s["z"], s["pred"] / pscale], 1)


cand_cal = calibrate(windows(both(v)[cal_parts], v["judged"][cal_parts]))
val = {
    "shipped": scores(windows(v["z"], v["judged"]), v["judged"], shipped_cal),
    "with predicted normals": scores(windows(both(v), v["judged"]), v["judged"], cand_cal),
}
val = {k: s[rest] for k, s in val.items()}
lv, kv = v["label"][rest], v["type"][rest]
result = {"validation (without the calibration half of its good parts)": compare(lv, kv, val)}
h = sets["held"]
hs = {
    "shipped": scores(windows(h["z"], h["judged"]), h["judged"], shipped_cal),
    "with predicted normals": scores(windows(both(h), h["judged"]), h["judged"], cand_cal),
}
result["held"] = held_out(h["label"], h["type"], hs, lv, val, "held")
corr = [
    float(np.corrcoef(p[j].ravel(), t[j].ravel())[0, 1])
    for p, t, j in zip(
        predict(a_def[:, PRIOR_Z], j_def).transpose(1, 0, 2, 3),
        b_def[:, NORMAL_Z].transpose(1, 0, 2, 3),
        [j_def] * 3,
        strict=True,
    )
]
result["train_defects_correlation_per_normal_channel"] = corr
print("correlation of predicted and true normal residuals on the training defects:", corr, flush=True)
json.dump(result, open(sys.argv[1], "w"), indent=1)
