"""Design data for rule 48 (used sets only: validation and held-out seeds 1145-1149, all decided on before): for
every part above the shipped second look's gate, candidate test statistics over the shipped proposals, each a
region's statistic against the same statistic of the references (the good training parts' left-out signed z,
refitted with the shipped recipe) in units of their 95th percentile above their median, the part's the largest:

- ``chi``: the shipped test (the region's mean chi-square over the channels);
- ``ringR``: the same after each channel's mean signed z over a ring around the region (its judged pixels between
  1 and R px outside it) is taken from the region's, for the part and for each reference alike: a change of
  appearance smoother than the region (light, exposure, the stray light's lobe) is taken out, a local one kept;
- ``own``: the same after the region's own channel means are taken out (its shape only);
- ``cK``: channel K's mean z^2 alone (the shipped model's features: 0 log I, 1 DoLP, 2-3 DoLP (cos 2 AoLP,
  sin 2 AoLP)); ``pol``: channels 1-3 together, the polarization without the intensity.

Writes OUT.npz with each set's window scores (robust SD over the good validation parts), labels, types and, for
the gated parts, each statistic. Usage: PYTHONPATH=. python design.py OUT.npz TRAIN VAL [HELDOUT ...]. The
references are kept in OUT.refs.pt and reused."""

from __future__ import annotations

import copy
import sys

import cv2
import numpy as np
import torch

from model.draem.checkpoint import load_checkpoint
from model.draem.second_look import proposals
from station.evaluation import model_split

MODEL = "model/weights/default"
RINGS = (3, 6)
BATCH = 50


def ring(reg: np.ndarray, r: int) -> np.ndarray:
    return cv2.dilate(reg.astype(np.uint8), np.ones((2 * r + 1, 2 * r + 1), np.uint8)).astype(bool) & ~reg


def stats(reg: np.ndarray, s: np.ndarray, j: np.ndarray) -> dict[str, np.ndarray]:
    """s (N, C, H, W) signed z (0 where not judged), j (N, H, W) judged -> each statistic (N,) over region reg."""
    jr = j[:, reg].astype(np.float32)  # (N, P)
    sr = s[:, :, reg].astype(np.float32)  # (N, C, P)
    n = np.maximum(jr.sum(1), 1.0)
    out = {"chi": (sr ** 2).sum(1).sum(1) / n, "pol": (sr[:, 1:] ** 2).sum(1).sum(1) / n}
    for c in range(sr.shape[1]):
        out[f"c{c}"] = (sr[:, c] ** 2).sum(1) / n
    mu = sr.sum(2) / n[:, None]
    out["own"] = (((sr - mu[:, :, None]) * jr[:, None]) ** 2).sum(1).sum(1) / n
    for r in RINGS:
        rg = ring(reg, r)
        jg = j[:, rg].astype(np.float32)
        mg = s[:, :, rg].astype(np.float32).sum(2) / np.maximum(jg.sum(1), 1.0)[:, None]
        out[f"ring{r}"] = (((sr - mg[:, :, None]) * jr[:, None]) ** 2).sum(1).sum(1) / n
    return out


def main() -> None:
    out, train, val, *heldout = sys.argv[1:]
    ck = load_checkpoint(MODEL)
    vm = copy.deepcopy(ck.detector.variation)
    look = vm.second_look
    gate, wl, ws = (float(v) for v in look.calibration[:3])
    look.calibration[0] = np.inf  # window scores alone
    cache = out + ".refs.pt"
    try:
        saved = torch.load(cache, weights_only=True)
        ref_s, ref_j = saved["signed"].float().numpy(), saved["judged"].numpy()
    except FileNotFoundError:
        tr = model_split(ck, MODEL, train, "train", good_only=True)
        fit = copy.deepcopy(vm)
        ref_s = fit.fit(tr.priors.float(), tr.object_mask)
        ref_j = (ref_s != 0).any(1)
        chi = (ref_s ** 2).sum(1)[:, vm.region.numpy()]
        print("references against the shipped file's: max |chi difference|",
              float(np.abs(np.minimum(chi, 6e4) - look.chi.float().numpy()).max()), flush=True)
        torch.save({"signed": torch.from_numpy(ref_s.astype(np.float16)), "judged": torch.from_numpy(ref_j)}, cache)
    print(f"references: {len(ref_s)}", flush=True)
    result = {"gate": gate}
    for name, root, split in (("val", val, "val"), *((f"h{k}", h, "test") for k, h in enumerate(heldout))):
        sp = model_split(ck, MODEL, root, split)
        x = sp.priors.float()
        win, rows = [], {}
        for i in range(0, len(x), BATCH):
            o = vm.zmaps(x[i:i + BATCH], signed=True)
            for k, (m, s, j) in enumerate(zip(o.maps.numpy(), o.signed.numpy(), o.judged.numpy(), strict=True)):
                w = (float(m.max()) - wl) / ws
                win.append(w)
                best: dict[str, float] = {}
                for reg in proposals(m):
                    own = stats(reg, s[None], j[None])
                    refs = stats(reg, ref_s, ref_j)
                    for key, r in refs.items():
                        med, q = float(np.median(r)), float(np.percentile(r, 95))
                        best[key] = max(best.get(key, 0.0), (float(own[key][0]) - med) / max(q - med, 1e-6))
                for key, v in best.items():
                    rows.setdefault(key, {})[i + k] = v
            print(f"{name}: {min(i + BATCH, len(x))}/{len(x)}", flush=True)
        n = len(win)
        result[f"{name}_window"] = np.array(win)
        result[f"{name}_label"] = sp.label.numpy()
        result[f"{name}_type"] = np.array([t or "" for t in sp.defect_type])
        for key, d in rows.items():
            a = np.full(n, np.nan)
            a[list(d)] = list(d.values())
            result[f"{name}_{key}"] = a
        np.savez(out, **result)
    print("done", flush=True)


if __name__ == "__main__":
    main()
