"""How many of the network's highest logits its finding should average (used sets only): for each part, the shipped
window score and second-look test (as nets50.py) and the shipped file's network's mean of its K highest logits over
the judged part, for K in KS (the file uses 10: ``model.draem.residual.TOP_K``). Columns ``C_k{K}`` for
screen50.py. Usage: PYTHONPATH=. python topk50.py OUT.npz VAL HELDOUT..."""

from __future__ import annotations

import copy
import sys

import numpy as np
import torch

from model.draem.checkpoint import load_checkpoint
from station.evaluation import model_split

MODEL = "model/weights/default"
BATCH = 50
KS = (3, 10, 30, 100, 300)


def main() -> None:
    out, val, *heldout = sys.argv[1:]
    ck = load_checkpoint(MODEL)
    det = ck.detector
    vm = copy.deepcopy(det.variation)
    look = vm.second_look
    gate, wl, ws, tl, ts = (float(v) for v in look.calibration)
    look.calibration[0] = np.inf  # window scores alone
    part = vm.region.numpy()
    result = {"gate": gate}
    for name, root, split in (("val", val, "val"), *((f"h{k}", h, "test") for k, h in enumerate(heldout))):
        sp = model_split(ck, MODEL, root, split)
        x = sp.priors.float()
        cols: dict[str, list[float]] = {"window": [], "chi": [], **{f"C_k{k}": [] for k in KS}}
        for i in range(0, len(x), BATCH):
            o = vm.zmaps(x[i:i + BATCH], signed=True)
            for m, s, j in zip(o.maps.numpy(), o.signed.numpy(), o.judged.numpy(), strict=True):
                cols["window"].append((float(m.max()) - wl) / ws)
                cols["chi"].append((look.test(m, (s.astype(np.float32) ** 2).sum(0), j, part) - tl) / ts)
            xin, judged = det.residual_inputs(o.signed, o.judged)
            j = judged.bool() | ~judged.flatten(1).any(1).view(-1, 1, 1)
            with torch.no_grad():
                logits = det.residual.members[0](xin).masked_fill(~j, -torch.inf).flatten(1)
            ranked = logits.sort(1, descending=True).values
            for k in KS:
                cols[f"C_k{k}"].extend(ranked[:, :k].double().mean(1).tolist())
            print(f"{name}: {min(i + BATCH, len(x))}/{len(x)}", flush=True)
        for k, v in cols.items():
            result[f"{name}_{k}"] = np.array(v)
        result[f"{name}_label"] = sp.label.numpy()
        result[f"{name}_type"] = np.array([t or "" for t in sp.defect_type])
        np.savez(out, **result)
    print("done", flush=True)


if __name__ == "__main__":
    main()
