"""Design data for rule 48, second screen (used sets only, as design.py): the shipped test against references
near the part in appearance. Good parts differ by a few scene causes (the light's position, exposure, the belt),
and a place's residual depends on them: a light far to one side lights the part's end and moves every stud's
shadow, in the part and in the good parts lit the same way alike, while a defect is where no good part has one.
So each region is tested against the K references nearest the part in the variation model's appearance
coefficients (divided by the clusters' spread, the clusters' own metric), K in KS (376: all, the shipped test).

Writes OUT.npz as design.py does, with statistics ``nearK``. Usage: PYTHONPATH=. python design2.py OUT.npz TRAIN
VAL [HELDOUT ...]; the references come from design.py's cache (REFS, its OUT.refs.pt)."""

from __future__ import annotations

import copy
import sys

import numpy as np
import torch

from model.draem.checkpoint import load_checkpoint
from model.draem.second_look import TAIL_QUANTILE, proposals
from station.evaluation import model_split

MODEL = "model/weights/default"
REFS = "runs/r48/design.npz.refs.pt"
KS = (20, 40, 80, 160, 376)
BATCH = 50


def main() -> None:
    out, train, val, *heldout = sys.argv[1:]
    ck = load_checkpoint(MODEL)
    vm = copy.deepcopy(ck.detector.variation)
    look = vm.second_look
    gate, wl, ws = (float(v) for v in look.calibration[:3])
    look.calibration[0] = np.inf  # window scores alone
    spread = vm.cluster_spread.numpy()
    saved = torch.load(REFS, weights_only=True)
    ref_chi = (saved["signed"].float().numpy() ** 2).sum(1)
    ref_j = saved["judged"].numpy().astype(np.float32)
    tr = model_split(ck, MODEL, train, "train", good_only=True)
    ref_coef = np.stack([vm._judged_residual(xi)[1] for xi in tr.priors.float().numpy()]) / spread
    print(f"references: {len(ref_chi)}, coefficients {ref_coef.shape}", flush=True)
    result = {"gate": gate}
    for name, root, split in (("val", val, "val"), *((f"h{k}", h, "test") for k, h in enumerate(heldout))):
        sp = model_split(ck, MODEL, root, split)
        x = sp.priors.float()
        win, rows = [], {k: [] for k in KS}
        for i in range(0, len(x), BATCH):
            o = vm.zmaps(x[i:i + BATCH], signed=True)
            for xi, m, s, j in zip(x[i:i + BATCH].numpy(), o.maps.numpy(), o.signed.numpy(), o.judged.numpy(),
                                   strict=True):
                win.append((float(m.max()) - wl) / ws)
                coef = vm._judged_residual(xi)[1] / spread
                order = np.argsort(((ref_coef - coef) ** 2).sum(1), kind="stable")
                chi = (s.astype(np.float32) ** 2).sum(0)
                best = dict.fromkeys(KS, 0.0)
                for reg in proposals(m):
                    r = ref_chi[:, reg].sum(1) / np.maximum(ref_j[:, reg].sum(1), 1.0)
                    own = float((chi * j)[reg].sum()) / max(float(j[reg].sum()), 1.0)
                    for k in KS:
                        rk = r[order[:k]]
                        med, q = float(np.median(rk)), float(np.percentile(rk, TAIL_QUANTILE))
                        best[k] = max(best[k], (own - med) / max(q - med, 1e-6))
                for k in KS:
                    rows[k].append(best[k])
            print(f"{name}: {min(i + BATCH, len(x))}/{len(x)}", flush=True)
        result[f"{name}_window"] = np.array(win)
        result[f"{name}_label"] = sp.label.numpy()
        result[f"{name}_type"] = np.array([t or "" for t in sp.defect_type])
        for k in KS:
            result[f"{name}_near{k}"] = np.array(rows[k])
        np.savez(out, **result)
    print("done", flush=True)


if __name__ == "__main__":
    main()
