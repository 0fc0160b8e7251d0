"""Rule 48's scores (rule48.md): for each part of each set, the shipped window score and the shipped second look's
test (both in robust SD over the good validation parts, as the shipped file puts them) and each residual-network
checkpoint's score (``station residual``'s calibrated score: robust SD over the same good validation parts). The
shipped variation model is used for all (the residual checkpoints carry a copy of it; checked equal).
Writes OUT.npz with ``{set}_window``, ``{set}_chi``, ``{set}_{net}``, labels and types; sets: val, then h0, h1, ...
Usage: PYTHONPATH=. python nets.py OUT.npz VAL HELDOUT... --nets NAME=CHECKPOINT..."""

from __future__ import annotations

import copy
import sys

import numpy as np
import torch

from model.draem.checkpoint import load_checkpoint
from model.draem.detector import Detector
from model.draem.residual import TOP_K
from station.evaluation import model_split

MODEL = "model/weights/default"
BATCH = 50


def top_logits(det: Detector, signed: torch.Tensor, judged: torch.Tensor) -> np.ndarray:
    """(N,) the mean of the TOP_K highest logits over the judged pixels, averaged over members: the networks'
    score before the sigmoid saturates it (``NET_logit``; put in robust SD by the analysis)."""
    x, j = det.residual_inputs(signed, judged)
    j = j | ~j.flatten(1).any(1).view(-1, 1, 1)  # nothing judged: the whole map, as member_scores
    with torch.no_grad():
        out = [m(x).masked_fill(~j, -torch.inf).flatten(1).topk(TOP_K, 1).values.mean(1)
               for m in det.residual.members]
    return torch.stack(out).mean(0).numpy()


def main() -> None:
    args = sys.argv[1:]
    cut = args.index("--nets")
    out, val, *heldout = args[:cut]
    nets = dict(a.split("=", 1) for a in args[cut + 1:])
    ck = load_checkpoint(MODEL)
    vm = copy.deepcopy(ck.detector.variation)
    look = vm.second_look
    gate, wl, ws, tl, ts = (float(v) for v in look.calibration)
    look.calibration[0] = np.inf  # window scores alone; the test computed here as the shipped file computes it
    part = vm.region.numpy()
    dets = {}
    for name, path in nets.items():
        d = load_checkpoint(path).detector
        same = all(torch.equal(a, b) for a, b in zip(d.variation.state_dict().values(),
                                                     ck.detector.variation.state_dict().values(), strict=True))
        print(f"{name}: {path}, variation model equal to the shipped file's: {same}", flush=True)
        dets[name] = d
    result = {"gate": gate}
    for name, root, split in (("val", val, "val"), *((f"h{k}", h, "test") for k, h in enumerate(heldout))):
        sp = model_split(ck, MODEL, root, split)
        x = sp.priors.float()
        cols: dict[str, list[float]] = {"window": [], "chi": [], **{n: [] for n in dets},
                                        **{n + "_logit": [] for n in dets}}
        for i in range(0, len(x), BATCH):
            o = vm.zmaps(x[i:i + BATCH], signed=True)
            for m, s, j in zip(o.maps.numpy(), o.signed.numpy(), o.judged.numpy(), strict=True):
                cols["window"].append((float(m.max()) - wl) / ws)
                cols["chi"].append((look.test(m, (s.astype(np.float32) ** 2).sum(0), j, part) - tl) / ts)
            for n, d in dets.items():
                cols[n].extend(d.residual_output(o.signed, o.judged).score.tolist())
                cols[n + "_logit"].extend(top_logits(d, o.signed, o.judged).tolist())
            print(f"{name}: {min(i + BATCH, len(x))}/{len(x)}", flush=True)
        for k, v in cols.items():
            result[f"{name}_{k}"] = np.array(v)
        result[f"{name}_label"] = sp.label.numpy()
        result[f"{name}_type"] = np.array([t or "" for t in sp.defect_type])
        np.savez(out, **result)
    print("done", flush=True)


if __name__ == "__main__":
    main()
