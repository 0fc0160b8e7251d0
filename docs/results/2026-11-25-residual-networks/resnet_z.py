"""A small segmentation network on the variation model's signed z maps (exploration, runs/s32)."""

from __future__ import annotations

import json
import sys
import time

import cv2
import numpy as np
import torch
import torch.nn as nn
import torch.nn.functional as F

from model.draem.variation import MEDIAN_ABS_NORMAL, NOISE_CAP

torch.set_num_threads(2)
c, c2 = np.load("runs/s32/zcache.npz"), np.load("runs/s32/zcache2.npz")
region = c["region"]
eroded = cv2.erode(region.astype(np.uint8), np.ones((3, 3), np.uint8)).astype(bool)
logspread = np.log(c["spread"]).astype(np.float32)
logspread = (logspread - logspread[region].mean()) / logspread[region].std()


def prep(z, judged):
    z = z.astype(np.float32)
    s = float(np.median(np.abs(z[:, judged]))) / MEDIAN_ABS_NORMAL if judged.any() else 1.0
    z = z / (s if 1.0 < s <= NOISE_CAP else 1.0)
    z = np.clip(z, -20, 20) * (judged & region)
    return np.concatenate([z, region[None].astype(np.float32), logspread[None] * region])


class Net(nn.Module):
    def __init__(self, w=16):
        super().__init__()

        def blk(i, o):
            return nn.Sequential(nn.Conv2d(i, o, 3, padding=1), nn.ReLU(), nn.Conv2d(o, o, 3, padding=1), nn.ReLU())

        self.e1, self.e2, self.e3 = blk(5, w), blk(w, 2 * w), blk(2 * w, 2 * w)
        self.d2, self.d1 = blk(4 * w, 2 * w), blk(3 * w, w)
        self.out = nn.Conv2d(w, 1, 1)

    def forward(self, x):
        a = self.e1(x)
        b = self.e2(F.max_pool2d(a, 2))
        d = self.e3(F.max_pool2d(b, 2))
        b = self.d2(torch.cat([b, F.interpolate(d, size=b.shape[2:])], 1))
        a = self.d1(torch.cat([a, F.interpolate(b, size=a.shape[2:])], 1))
        return self.out(a)[:, 0]


def synthetic(rng, z, judged):
    """Add one anomaly: a random smooth shape inside the judged part, signed amplitudes per channel."""
    h, w = judged.shape
    for _ in range(20):
        kind = rng.integers(3)
        m = np.zeros((h, w), np.float32)
        cy, cx = rng.integers(0, h), rng.integers(0, w)
        if not judged[cy, cx]:
            continue
        if kind == 0:  # blob
            ax = rng.uniform(1.5, 12), rng.uniform(1.5, 12)
            cv2.ellipse(m, (int(cx), int(cy)), (int(ax[0]), int(ax[1])), rng.uniform(0, 180), 0, 360, 1.0, -1)
        elif kind == 1:  # line
            L, a = rng.uniform(8, 50), rng.uniform(0, np.pi)
            p0 = (int(cx - L / 2 * np.cos(a)), int(cy - L / 2 * np.sin(a)))
            p1 = (int(cx + L / 2 * np.cos(a)), int(cy + L / 2 * np.sin(a)))
            cv2.line(m, p0, p1, 1.0, int(rng.integers(1, 4)))
        else:  # noise-thresholded patch
            n = cv2.GaussianBlur(rng.standard_normal((h, w)).astype(np.float32), (0, 0), rng.uniform(2, 6))
            n = n / n.std()
            box = np.zeros((h, w), bool)
            r = int(rng.integers(6, 25))
            box[max(cy - r, 0) : cy + r, max(cx - r, 0) : cx + r] = True
            m = ((n > 1.0) & box).astype(np.float32)
        m *= judged
        if m.sum() < 3:
            continue
        soft = cv2.GaussianBlur(m, (0, 0), 0.7)
        amp = rng.uniform(-1, 1, 3) * rng.uniform(0.5, 4.0)
        if rng.random() < 0.5:  # a tilt-like signed pattern: the shape's gradient
            gy, gx = np.gradient(cv2.GaussianBlur(m, (0, 0), 1.5))
            a = rng.uniform(0, 2 * np.pi)
            pat = np.cos(a) * gx + np.sin(a) * gy
            pat /= np.abs(pat).max() + 1e-6
            soft = np.abs(pat)
            add = amp[:, None, None] * pat[None]
        else:
            add = amp[:, None, None] * soft[None]
        z = z.copy()
        z[:3] += add * judged
        return z, (soft > 0.25).astype(np.float32)
    return z, np.zeros((h, w), np.float32)


def dataset(exclude: str | None):
    xs, ms, goods = [], [], []
    for z in c["train_z"]:
        xs.append(prep(z, region))
        ms.append(np.zeros(region.shape, np.float32))
        goods.append(True)
    for z, j, mk, t in zip(c2["trdef_z"], c2["trdef_judged"], c2["trdef_wmask"], c2["trdef_type"], strict=True):
        if t == exclude:
            continue
        xs.append(prep(z, j))
        ms.append((mk & region).astype(np.float32))
        goods.append(False)
    return np.stack(xs), np.stack(ms), np.array(goods)


def score_maps(net, zs, judged, bs=32):
    net.eval()
    out = []
    with torch.no_grad():
        for i in range(0, len(zs), bs):
            batch = zip(zs[i : i + bs], judged[i : i + bs], strict=True)
            x = torch.from_numpy(np.stack([prep(z, j) for z, j in batch]))
            out.append(torch.sigmoid(net(x)).numpy())
    net.train()
    return np.concatenate(out)


def image_scores(maps, judged, k=10):
    s = []
    for mp, j in zip(maps, judged, strict=True):
        v = np.sort(mp[eroded & j])[-k:]
        s.append(float(v.mean()) if len(v) else 0.0)
    return np.array(s)


def train(exclude=None, steps=3000, seed=0, log=None):
    rng = np.random.default_rng(seed)
    torch.manual_seed(seed)
    X, M, G = dataset(exclude)
    net = Net()
    opt = torch.optim.Adam(net.parameters(), 1e-3)
    sched = torch.optim.lr_scheduler.MultiStepLR(opt, [int(steps * 0.8)], 0.2)
    gi, di = np.where(G)[0], np.where(~G)[0]
    t0 = time.time()
    for step in range(steps):
        idx = np.concatenate([rng.choice(gi, 12), rng.choice(di, 4)])
        xb, mb = [], []
        for i in idx:
            x, m = X[i], M[i]
            if G[i] and rng.random() < 0.5:
                x, m = synthetic(rng, x, region & (x[3] > 0))
            y0, x0 = rng.integers(0, 96 - 64 + 1), rng.integers(0, 192 - 96 + 1)
            xb.append(x[:, y0 : y0 + 64, x0 : x0 + 96])
            mb.append(m[y0 : y0 + 64, x0 : x0 + 96])
        xb, mb = torch.from_numpy(np.stack(xb)), torch.from_numpy(np.stack(mb))
        logit = net(xb)
        inside = xb[:, 3] > 0
        pix = F.binary_cross_entropy_with_logits(logit[inside], mb[inside], pos_weight=torch.tensor(5.0))
        top = logit.masked_fill(~inside, -30).flatten(1).topk(10, 1).values.mean(1)
        img = F.binary_cross_entropy_with_logits(top, (mb.flatten(1).amax(1) > 0).float())
        loss = pix + 0.5 * img
        opt.zero_grad()
        loss.backward()
        opt.step()
        sched.step()
        if step % 250 == 0 and log:
            print(f"step {step} loss {loss.item():.4f} {time.time() - t0:.0f}s", file=log, flush=True)
    return net


if __name__ == "__main__":
    exclude = sys.argv[1] if len(sys.argv) > 1 and sys.argv[1] != "none" else None
    steps = int(sys.argv[2]) if len(sys.argv) > 2 else 3000
    net = train(exclude, steps, log=sys.stdout)
    tag = exclude or "all"
    torch.save(net.state_dict(), f"runs/s32/net-{tag}.pt")
    out = {}
    for split in ("val", "held"):
        mp = score_maps(net, c[f"{split}_z"], c[f"{split}_judged"])
        out[split] = image_scores(mp, c[f"{split}_judged"]).tolist()
        np.save(f"runs/s32/maps-{tag}-{split}.npy", mp.astype(np.float16))
    json.dump(out, open(f"runs/s32/net-{tag}.json", "w"))
    print("done", flush=True)
