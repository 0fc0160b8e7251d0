"""Rule 50's scores (rule50.md): for each part of each set, the shipped window score and the shipped second look's
test (robust SD over the good validation parts, as the shipped file puts them) and, for each checkpoint with
residual networks, each member's mean top-10 logits over the judged part (``ResidualDetector.top_logits`` for that
member alone) and the members' mean (what the file's own look reads). The shipped variation model is used for all:
the checkpoints carry a copy of it (checked equal). ``nets.py`` of the second-look page, with members apart.
Writes OUT.npz with ``{set}_window``, ``{set}_chi``, ``{set}_{net}_m{k}``, ``{set}_{net}``, labels and types;
sets: val, then h0, h1, ... Usage: PYTHONPATH=. python nets50.py OUT.npz VAL HELDOUT... --nets NAME=CHECKPOINT..."""

from __future__ import annotations

import copy
import sys

import numpy as np
import torch

from model.draem.checkpoint import load_checkpoint
from station.evaluation import model_split

MODEL = "model/weights/default"
BATCH = 50


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
        print(f"{name}: {path}, {len(d.residual.members)} members, variation model equal to the shipped file's: "
              f"{same}", flush=True)
        dets[name] = d
    result = {"gate": gate}
    for name, root, split in (("val", val, "val"), *((f"h{k}", h, "test") for k, h in enumerate(heldout))):
        sp = model_split(ck, MODEL, root, split)
        x = sp.priors.float()
        cols: dict[str, list[float]] = {"window": [], "chi": []}
        for i in range(0, len(x), BATCH):
            o = vm.zmaps(x[i:i + BATCH], signed=True)
            for m, s, j in zip(o.maps.numpy(), o.signed.numpy(), o.judged.numpy(), strict=True):
                cols["window"].append((float(m.max()) - wl) / ws)
                cols["chi"].append((look.test(m, (s.astype(np.float32) ** 2).sum(0), j, part) - tl) / ts)
            for n, d in dets.items():
                members, each = d.residual.members, []
                for k in range(len(members)):  # one member at a time: its own top logits
                    d.residual.members = members[k:k + 1]
                    each.append(d.residual.top_logits(*d.residual_inputs(o.signed, o.judged)).numpy())
                    cols.setdefault(f"{n}_m{k}", []).extend(each[-1].tolist())
                d.residual.members = members
                cols.setdefault(n, []).extend(np.mean(each, 0).tolist())  # = top_logits over all members
            print(f"{name}: {min(i + BATCH, len(x))}/{len(x)}", flush=True)
        for k, v in cols.items():
            result[f"{name}_{k}"] = np.array(v)
        result[f"{name}_label"] = sp.label.numpy()
        result[f"{name}_type"] = np.array([t or "" for t in sp.defect_type])
        np.savez(out, **result)
    print("done", flush=True)


if __name__ == "__main__":
    main()
