"""Residual networks trained on good parts only, with physically coupled synthetic anomalies (rule 3, rule.md).

Usage: train.py GENERATOR SEED [STEPS] (GENERATOR: physical | shipped), from the repository root, after the
residual-network study's cache.py (runs/s33/zcache.npz). Writes runs/s33/net-GENERATOR-SEED.{pt,json}: raw image
scores of the validation and held-out parts (and of held-out set 212 when runs/s33/zcache212.npz exists).

A physical anomaly changes the part's features as a change of its surface would (convention: features as in
model.draem.variation: log intensity, and (S1, S2) / S0 of the Stokes vector; AoLP counted counter-clockwise from
image right, so the direction of angle t in (x, y-down) pixels is (cos t, -sin t)). Where the good parts' mean
Stokes components are s = rho (cos 2 phi, sin 2 phi):
- a tilt (a dent, a bump, a groove's walls): the slope field d of a smooth height bump tilts the normal; its part
  along the normal's azimuth in the image (phi for diffuse, phi + 90 deg for specular polarization) changes the
  zenith angle, which scales rho (ds along s, sign and size unknown: k_par in +-1.5); its part across the azimuth
  rotates AoLP by that much (ds = 2 rho dphi along s rotated 90 deg, k_perp 0.5-2); intensity changes as shading
  along a random light direction;
- a material change (a stain, a rougher or glossier patch, contamination): over a soft patch the polarization is
  scaled by kappa in 0.3-1.8 and rotated by up to 0.3 rad, and the intensity by 0.5-1.5.
Each feature change is divided by the good parts' spread there (channel scale x residual scale), so it lands in the
signed z maps' units, and the whole anomaly is scaled so its largest |z| is 0.5-4 (as the shipped generator).
"""

from __future__ import annotations

import json
import sys
import time
from pathlib import Path

import cv2
import numpy as np
import torch

from model.draem.residual import CROP, TOP_K, ResidualNet, shape_mask, synthetic_anomaly, training_loss
from model.draem.variation import MEDIAN_ABS_NORMAL, NOISE_CAP, SIGNED_CLIP

torch.set_num_threads(2)
RUNS = Path("runs/s33")
c = np.load(RUNS / "zcache.npz")
region = c["region"]
eroded = cv2.erode(region.astype(np.uint8), np.ones((3, 3), np.uint8)).astype(bool)
logspread = np.log(c["spread"]).astype(np.float32)
logspread = ((logspread - logspread[region].mean()) / logspread[region].std()) * region
# the model's features (4 channels: log I, DoLP (not read: zero), S1/S0, S2/S0) -> the 3 read ones
mean = np.delete(c["mean"], 1, 0)
spread_f = np.delete(c["channel_scale"][:, None, None] * c["scale"], 1, 0)  # feature units per z unit
s_bar = mean[1:3]
rho = np.hypot(*s_bar)
phi = 0.5 * np.arctan2(s_bar[1], s_bar[0])
s_hat = s_bar / np.maximum(rho, 1e-4)
t_hat = np.stack([-s_hat[1], s_hat[0]])
stokes_in = (s_bar / np.median(spread_f[1:3][:, region], 1)[:, None, None] * region).astype(np.float32)


def prep(z, judged, with_mean):
    z = z.astype(np.float32)
    s = float(np.median(np.abs(z[:, judged]))) / MEDIAN_ABS_NORMAL if judged.any() else 1.0
    z = np.clip(z / (s if 1.0 < s <= NOISE_CAP else 1.0), -SIGNED_CLIP, SIGNED_CLIP) * (judged & region)
    extra = [region[None].astype(np.float32), logspread[None]] + ([stokes_in] if with_mean else [])
    return np.concatenate([z, *extra]).astype(np.float32)


def physical_anomaly(rng, z, judged):
    m = shape_mask(rng, judged)
    if m is None:
        return z, np.zeros(judged.shape, np.float32)
    df = np.zeros_like(mean)
    if rng.random() < 0.5:  # tilt
        hgt = cv2.GaussianBlur(m, (0, 0), rng.uniform(1.0, 3.0)) * rng.choice([-1.0, 1.0])
        gy, gx = np.gradient(hgt)
        az = phi + (np.pi / 2 if rng.random() < 0.5 else 0.0) + rng.normal(0, 0.1)
        along = gx * np.cos(az) - gy * np.sin(az)
        across = -gx * np.sin(az) - gy * np.cos(az)
        df[1:3] = rho * (rng.uniform(-1.5, 1.5) * along * s_hat + 2 * rng.uniform(0.5, 2.0) * across * t_hat)
        light = rng.uniform(0, 2 * np.pi)
        df[0] = rng.uniform(0.0, 2.0) * (gx * np.cos(light) - gy * np.sin(light))
        soft = np.hypot(gx, gy)
        soft = soft / (soft.max() + 1e-9)
    else:  # material
        soft = cv2.GaussianBlur(m, (0, 0), rng.uniform(0.5, 1.5))
        kappa, w = rng.uniform(0.3, 1.8), rng.uniform(-0.3, 0.3)
        rot = np.array([[np.cos(2 * w), -np.sin(2 * w)], [np.sin(2 * w), np.cos(2 * w)]])
        df[1:3] = (kappa * np.einsum("ij,jhw->ihw", rot, s_bar) - s_bar) * soft
        df[0] = np.log(rng.uniform(0.5, 1.5)) * soft
    dz = df / spread_f * judged
    peak = np.abs(dz).max()
    if not np.isfinite(peak) or peak < 1e-9:
        return z, np.zeros(judged.shape, np.float32)
    dz *= rng.uniform(0.5, 4.0) / peak
    return (z + dz).astype(np.float32), ((soft > 0.25) & judged).astype(np.float32)


def train(generator, seed, steps, log=sys.stdout):
    rng = np.random.default_rng(seed)
    torch.manual_seed(seed)
    with_mean = generator == "physical"
    good = np.stack([prep(z, region, with_mean) for z in c["train_z"]])
    nz = 3
    net = ResidualNet(good.shape[1])
    opt = torch.optim.Adam(net.parameters(), 1e-3)
    sched = torch.optim.lr_scheduler.MultiStepLR(opt, [int(steps * 0.8)], 0.2)
    ch, cw = CROP
    t0 = time.time()
    for step in range(steps):
        xb, mb = [], []
        for _ in range(16):
            x = good[int(rng.integers(len(good)))]
            m = np.zeros(region.shape, np.float32)
            if rng.random() < 0.5:
                judged = x[nz] > 0
                if generator == "physical":
                    zz, m = physical_anomaly(rng, x[:nz], judged)
                else:
                    zz, m = synthetic_anomaly(rng, x[:nz], judged)
                x = np.concatenate([zz, x[nz:]])
            y0, x0 = int(rng.integers(0, x.shape[1] - ch + 1)), int(rng.integers(0, x.shape[2] - cw + 1))
            xb.append(x[:, y0 : y0 + ch, x0 : x0 + cw])
            mb.append(m[y0 : y0 + ch, x0 : x0 + cw])
        xt, mt = torch.from_numpy(np.stack(xb)), torch.from_numpy(np.stack(mb))
        loss = training_loss(net(xt), mt, xt[:, nz] > 0)
        opt.zero_grad()
        loss.backward()
        opt.step()
        sched.step()
        if step % 250 == 0 or step == steps - 1:
            print(f"step {step} loss {loss.item():.4f} {time.time() - t0:.0f}s", file=log, flush=True)
    net.eval()
    return net, with_mean


def image_scores(net, zs, judged, with_mean, bs=32):
    out = []
    with torch.no_grad():
        for i in range(0, len(zs), bs):
            batch = zip(zs[i : i + bs], judged[i : i + bs], strict=True)
            x = torch.from_numpy(np.stack([prep(z, j, with_mean) for z, j in batch]))
            p = torch.sigmoid(net(x)).numpy()
            for mp, j in zip(p, judged[i : i + bs], strict=True):
                v = np.sort(mp[eroded & j])[-TOP_K:]
                out.append(float(v.mean()) if len(v) else 0.0)
    return out


if __name__ == "__main__":
    generator, seed = sys.argv[1], int(sys.argv[2])
    steps = int(sys.argv[3]) if len(sys.argv) > 3 else 3000
    net, with_mean = train(generator, seed, steps)
    tag = f"{generator}-{seed}"
    torch.save(net.state_dict(), RUNS / f"net-{tag}.pt")
    out = {split: image_scores(net, c[f"{split}_z"], c[f"{split}_judged"], with_mean) for split in ("val", "held")}
    if (RUNS / "zcache212.npz").exists():
        c212 = np.load(RUNS / "zcache212.npz")
        out["held212"] = image_scores(net, c212["held_z"], c212["held_judged"], with_mean)
    json.dump(out, open(RUNS / f"net-{tag}.json", "w"))
    print("done", flush=True)
