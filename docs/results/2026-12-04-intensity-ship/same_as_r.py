"""Is make model's file S the rule's fit R (../2026-12-04-intensity-robust.md) in what decides? Tensor by tensor.

    PYTHONPATH=. .venv/bin/python docs/results/2026-12-04-intensity-ship/same_as_r.py > .../same-as-r.txt

Both were fitted by the same commands on the same sets (the variation model, its look network, the threshold); they
differ in the DRAEM shell under them, which does not decide. Prints, per part of the checkpoint, how many tensors are
equal and which differ, and both stored thresholds.
"""
import json
import sys
from collections import Counter

import torch

R, S = sys.argv[1:3] if len(sys.argv) > 2 else ("runs/ir/R-look", "runs/make-model-r/band-look")


def main() -> None:
    a, b = (torch.load(f"{p}.pt", map_location="cpu", weights_only=False) for p in (R, S))
    same, differ = Counter(), Counter()
    for k, v in a.items():
        (same if torch.equal(v, b[k]) else differ)[k.split(".")[0]] += 1
        if not torch.equal(v, b[k]) and not k.startswith("members."):
            print(f"{k} differs: R {v.tolist()} S {b[k].tolist()}")
    assert set(a) == set(b)
    print(f"equal tensors per part: {dict(same)}; differing: {dict(differ)}")
    print("thresholds: " + ", ".join(f"{p} {json.load(open(f'{p}.json'))['threshold']!r}" for p in (R, S)))


if __name__ == "__main__":
    main()
