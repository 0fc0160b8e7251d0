"""The synthetic-anomaly row of `station eval` on seed 1149 (the shipped file with the second look), anomaly by
anomaly: the lowest-scoring synthetic anomalies (the same draw as `station eval`'s, seed 4242), their mask in the
variation model's frame and how much of it it judges (highlights are not judged), and how many good parts score
above each. Usage: PYTHONPATH=. python synthetic.py (from the repository root)."""

import numpy as np

from model.draem.checkpoint import load_checkpoint
from model.draem.evaluate import evaluate, synthetic_eval_data
from model.draem.metrics import auroc
from model.draem.train import TensorData
from station.evaluation import model_split

M = "model/weights/default"
ck = load_checkpoint(M)
for data in ("data/line-panel-heldout-1149",):
    sp = model_split(ck, M, data, "test")
    good = sp.label == 0
    syn = synthetic_eval_data(TensorData(sp.priors[good], sp.object_mask[good]), ck.detector.config.priors, seed=4242)
    ev = evaluate(ck.detector, syn)
    y, s = syn.label.numpy(), ev.scores
    vm = ck.detector.variation
    o = vm.zmaps(syn.priors.float(), signed=True)
    judged = o.judged.numpy()
    reg = vm.register_masks(syn.priors.float(), syn.defect_mask.bool()).numpy()
    print(data, "synthetic AUROC", round(auroc(y, s), 4), "anomalous", int(y.sum()), "good", int((1 - y).sum()))
    gmax = np.sort(s[y == 0])[::-1][:3]
    print(" top good scores", np.round(gmax, 3))
    idx = np.flatnonzero(y == 1)
    low = idx[np.argsort(s[idx])[:8]]
    for i in low:
        area, inj = reg[i].sum(), (reg[i] & judged[i]).sum()
        print(f"  anomaly {i}: score {s[i]:.3f}, mask {area} px, judged {inj} px ({inj / max(area, 1):.0%}), "
              f"good parts above it: {(s[y == 0] > s[i]).sum()}")
