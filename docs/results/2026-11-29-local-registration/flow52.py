"""Screen (used sets only): does a local registration after the affine one take in the good tail?
The shipped variation model is fitted again as the file's recipe (8 clusters, blurred copies, contrast mean,
polarization range, second look) twice on the same good training parts: A with the affine ECC registration alone
(the shipped ``warp_to``), B with a smoothed dense flow after it (``refine``: Farneback flow of the warped
intensity feature against the reference, averaged by normalised convolution weighted by the reference's squared
gradient, Gaussian sigma SIGMA input px, clipped to MAX_PX). Each part's window score and second-look test, in
robust SD over the good validation parts, are written to OUT.npz as ``{fit}_{set}_window`` / ``_chi``.
Usage: PYTHONPATH=. python flow52.py OUT.npz SIGMA MAX_PX dense|modesK|guardK VAL HELDOUT..."""

from __future__ import annotations

import copy
import sys

import cv2
import numpy as np
import torch

from model.draem.checkpoint import load_checkpoint
from model.draem.variation import VariationModel
from model.draem.with_variation import second_look_scores
from station.evaluation import model_split

MODEL = "model/weights/default"
BATCH = 50
affine_warp = VariationModel.warp_to


def dense_flow(self, reference, w, mask, sigma):
    """Smoothed flow (H, W, 2) of warped features ``w`` onto ``reference`` and its per-pixel weight (H, W)."""
    lo, hi = np.percentile(reference, [1, 99])
    to8 = lambda a: np.clip((a - lo) / max(hi - lo, 1e-6) * 255, 0, 255).astype(np.uint8)  # noqa: E731
    flow = cv2.calcOpticalFlowFarneback(to8(reference), to8(w[self.intensity]), None, 0.5, 3, 15, 3, 5, 1.1, 0)
    gx = cv2.Sobel(reference, cv2.CV_32F, 1, 0)
    gy = cv2.Sobel(reference, cv2.CV_32F, 0, 1)
    wt = gx ** 2 + gy ** 2
    if mask is not None:
        wt = wt * mask
    den = cv2.GaussianBlur(wt, (0, 0), sigma) + 1e-9
    fx = cv2.GaussianBlur(wt * flow[..., 0], (0, 0), sigma) / den
    fy = cv2.GaussianBlur(wt * flow[..., 1], (0, 0), sigma) / den
    return np.stack([fx, fy], -1), den


def remapped(w, fx, fy):
    h, ww = w.shape[1:]
    yy, xx = np.mgrid[0:h, 0:ww].astype(np.float32)
    mx, my = (xx + fx).astype(np.float32), (yy + fy).astype(np.float32)
    return np.stack([cv2.remap(c, mx, my, cv2.INTER_LINEAR, borderMode=cv2.BORDER_REPLICATE) for c in w])


MODES: dict[str, np.ndarray] = {}


def modes_with(sigma: float, max_px: float):
    """The dense flow projected onto MODES["m"] (K, H, W, 2), weighted by the smoothed gradient weight; the
    coefficients clipped to MODES["lo"], MODES["hi"]."""
    def warp_to(self, reference, f, mask=None):
        w = affine_warp(self, reference, f, mask)
        flow, wt = dense_flow(self, reference, w, mask, sigma)
        m = MODES["m"]
        a = (m.reshape(len(m), -1, 2) * np.sqrt(wt).reshape(1, -1, 1)).reshape(len(m), -1).T
        b = (flow.reshape(-1, 2) * np.sqrt(wt).reshape(-1, 1)).reshape(-1)
        c = np.clip(np.linalg.lstsq(a, b, rcond=None)[0], MODES["lo"], MODES["hi"])
        fl = np.tensordot(c, m, 1)
        r = remapped(w, fl[..., 0], fl[..., 1])
        if GUARD and ncc(reference, r[self.intensity], mask) < ncc(reference, w[self.intensity], mask):
            return w  # the refinement matches the reference worse than the affine warp: keep the affine warp
        return r
    return warp_to


GUARD = False


def ncc(a, b, mask) -> float:
    """Normalised cross-correlation of (H, W) ``a`` and ``b`` where ``mask`` (all pixels when None)."""
    m = np.ones(a.shape, bool) if mask is None else mask.astype(bool)
    x, y = a[m] - a[m].mean(), b[m] - b[m].mean()
    return float((x * y).sum() / (np.sqrt((x * x).sum() * (y * y).sum()) + 1e-12))


def learn_modes(vm, tr, k: int, sigma: float) -> None:
    """MODES from the good training parts' smoothed flows onto ``vm``'s (affine-fitted) reference."""
    ref = vm.reference.numpy()
    region = vm.region.numpy()
    flows = []
    for xi in tr.priors.float().numpy():
        f = vm.features(xi)
        w = affine_warp(vm, ref, f)
        flows.append(dense_flow(vm, ref, w, None, sigma)[0] * region[..., None])
    flows = np.stack(flows)
    flat = flows.reshape(len(flows), -1)
    mean = flat.mean(0)
    _, sv, vt = np.linalg.svd(flat - mean, full_matrices=False)
    m = np.concatenate([mean[None], vt[:k]]).reshape(k + 1, *flows.shape[1:])
    coef = np.linalg.lstsq(m.reshape(k + 1, -1).T, flat.T, rcond=None)[0].T
    MODES.update(m=m, lo=coef.min(0), hi=coef.max(0))
    print(f"modes: singular values {np.round(sv[:6], 1)}, coefficient ranges {np.round(coef.min(0), 2)} .. "
          f"{np.round(coef.max(0), 2)}", flush=True)


def refine_with(sigma: float, max_px: float):
    """The dense flow (``dense_flow``) clipped to ``max_px``."""
    def warp_to(self, reference, f, mask=None):
        w = affine_warp(self, reference, f, mask)
        flow = dense_flow(self, reference, w, mask, sigma)[0]
        cut = np.minimum(1.0, max_px / np.maximum(np.hypot(flow[..., 0], flow[..., 1]), 1e-9))
        return remapped(w, flow[..., 0] * cut, flow[..., 1] * cut)
    return warp_to


def fitted(ck, tr, va_good) -> VariationModel:
    vm = copy.deepcopy(ck.detector.variation)
    refs = vm.fit(tr.priors, tr.object_mask if tr.object_masks_known else None)
    vm.second_look.fit(refs, vm.region.numpy())
    vm.second_look.calibrate(*second_look_scores(vm, va_good, 16))
    return vm


def scores(vm: VariationModel, x: torch.Tensor) -> tuple[np.ndarray, np.ndarray]:
    look = vm.second_look
    gate, wl, ws, tl, ts = (float(v) for v in look.calibration)
    look.calibration[0] = np.inf
    part = vm.region.numpy()
    win, chi = [], []
    for i in range(0, len(x), BATCH):
        o = vm.zmaps(x[i:i + BATCH], signed=True)
        for m, s, j in zip(o.maps.numpy(), o.signed.numpy(), o.judged.numpy(), strict=True):
            win.append((float(m.max()) - wl) / ws)
            chi.append((look.test(m, (s.astype(np.float32) ** 2).sum(0), j, part) - tl) / ts)
    look.calibration[0] = gate
    return np.array(win), np.array(chi)


def main() -> None:
    out, sigma, max_px, kind, val, *held = sys.argv[1:]
    ck = load_checkpoint(MODEL)
    tr = model_split(ck, MODEL, "data/line-panel-train", "train", good_only=True)
    sets = {"val": model_split(ck, MODEL, val, "val")}
    for k, h in enumerate(held):
        sets[f"h{k}"] = model_split(ck, MODEL, h, "test")
    va_good = sets["val"].priors[sets["val"].label == 0].float()
    result: dict[str, np.ndarray] = {}
    vm: VariationModel | None = None
    for name in ("A", "B"):
        if vm is None:
            VariationModel.warp_to = affine_warp
        elif kind == "dense":
            VariationModel.warp_to = refine_with(float(sigma), float(max_px))
        else:  # "modesK" (or "guardK": kept only where it raises the NCC with the reference): K flow modes
            # learned on the good training parts against A's reference
            global GUARD
            GUARD = kind.startswith("guard")
            learn_modes(vm, tr, int(kind[5:]), float(sigma))
            VariationModel.warp_to = modes_with(float(sigma), float(max_px))
        vm = fitted(ck, tr, va_good)
        result[f"{name}_gate"] = np.array(float(vm.second_look.calibration[0]))
        print(f"{name}: fitted, gate {float(vm.second_look.calibration[0]):.3f}", flush=True)
        for s, sp in sets.items():
            w, c = scores(vm, sp.priors.float())
            result[f"{name}_{s}_window"], result[f"{name}_{s}_chi"] = w, c
            result[f"{s}_label"] = sp.label.numpy()
            result[f"{s}_type"] = np.array([t or "" for t in sp.defect_type])
            print(f"{name}: {s} scored", flush=True)
            np.savez(out, **result)
    VariationModel.warp_to = affine_warp
    print("done", flush=True)


if __name__ == "__main__":
    main()
