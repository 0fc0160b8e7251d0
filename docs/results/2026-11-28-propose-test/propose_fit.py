"""Propose and test with the references a model would carry: the shipped variation model fitted again on the good
training parts (the shipped recipe), their left-out signed z as the reference; each scored part's K highest places
of the model's own window map propose regions (the map above FRAC of the place's peak, connected, at most MAXPX
px, grown 1 px), each tested as the localised oracle tests a defect's pixels (the mean chi-square over the channels
there against the references' same mean, in units of their 95th percentile above their median); the part's score
is the largest. Writes each set's box (shipped) and propose scores.

Usage: PYTHONPATH=. python propose_fit.py OUT.npz TRAIN VAL [HELDOUT ...] (from the repository root). The fit and
its references are kept in OUT.fit.pt and reused by a later run with the same OUT."""

from __future__ import annotations

import copy
import sys

import cv2
import numpy as np
import torch

from model.draem.checkpoint import load_checkpoint
from station.evaluation import model_split

MODEL = "model/weights/default"
K, FRAC, MAXPX, BATCH = 5, 0.5, 400, 50


def proposals(m: np.ndarray) -> list[np.ndarray]:
    """The K highest places of a window map, each as the region around it (module docstring)."""
    out, m = [], m.copy()
    for _ in range(K):
        peak = float(m.max())
        if peak <= 0:
            break
        y, x = np.unravel_index(int(m.argmax()), m.shape)
        _, comp = cv2.connectedComponents((m >= FRAC * peak).astype(np.uint8), connectivity=8)
        reg = comp == comp[y, x]
        if reg.sum() > MAXPX:  # the MAXPX pixels nearest the peak
            yy, xx = np.nonzero(reg)
            keep = np.argsort((yy - y) ** 2 + (xx - x) ** 2)[:MAXPX]
            reg = np.zeros_like(reg)
            reg[yy[keep], xx[keep]] = True
        reg = cv2.dilate(reg.astype(np.uint8), np.ones((3, 3), np.uint8)).astype(bool)
        out.append(reg)
        m[cv2.dilate(reg.astype(np.uint8), np.ones((5, 5), np.uint8)).astype(bool)] = 0
    return out


def main() -> None:
    out, train, val, *heldout = sys.argv[1:]
    ck = load_checkpoint(MODEL)
    vm = copy.deepcopy(ck.detector.variation)
    cache = out + ".fit.pt"
    try:
        saved = torch.load(cache, weights_only=True)
        vm.size_clusters(saved["state"])
        vm.load_state_dict(saved["state"])
        ref_chi, ref_judged = saved["ref_chi"].numpy(), saved["ref_judged"].numpy()
    except FileNotFoundError:
        tr = model_split(ck, MODEL, train, "train", good_only=True)
        ref = vm.fit(tr.priors.float(), tr.object_mask)  # (N, C, H, W) left-out signed z, zero where not judged
        ref_chi = (ref.astype(np.float32) ** 2).sum(1)
        ref_judged = (ref != 0).any(1).astype(np.float32)
        torch.save({"state": vm.state_dict(), "ref_chi": torch.from_numpy(ref_chi),
                    "ref_judged": torch.from_numpy(ref_judged)}, cache)
    print(f"references: {len(ref_chi)} good training parts", flush=True)
    shipped = ck.detector.variation
    result = {}
    for name, root, split in (("val", val, "val"), *((f"heldout{k}", h, "test") for k, h in enumerate(heldout))):
        sp = model_split(ck, MODEL, root, split)
        x = sp.priors.float()
        box, test, same = [], [], []
        for i in range(0, len(x), BATCH):
            o = vm.zmaps(x[i:i + BATCH], signed=True)
            same.append(shipped.zmaps(x[i:i + BATCH]).scores.numpy())
            chi = (o.signed.numpy() ** 2).sum(1)
            judged = o.judged.numpy()
            for m, c, j in zip(o.maps.numpy(), chi, judged, strict=True):
                best = 0.0
                for reg in proposals(m):
                    r = ref_chi[:, reg].sum(1) / np.maximum(ref_judged[:, reg].sum(1), 1.0)
                    own = float((c * j)[reg].sum()) / max(float(j[reg].sum()), 1.0)
                    med, q = float(np.median(r)), float(np.percentile(r, 95))
                    best = max(best, (own - med) / max(q - med, 1e-6))
                test.append(best)
            box.append(o.scores.numpy())
        box, same = np.concatenate(box), np.concatenate(same)
        print(f"{name}: {len(box)} parts; refit against shipped box scores: max |difference| "
              f"{float(np.abs(box - same).max()):.3g}", flush=True)
        result.update({f"{name}_box": box, f"{name}_shipped": same, f"{name}_test": np.array(test),
                       f"{name}_label": sp.label.numpy(),
                       f"{name}_type": np.array([t or "" for t in sp.defect_type]),
                       f"{name}_index": np.array(sp.index)})
    np.savez(out, **result)


if __name__ == "__main__":
    main()
