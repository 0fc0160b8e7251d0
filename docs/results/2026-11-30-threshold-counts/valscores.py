"""Per-part val scores of both cameras' files on seed 303's twins (as station split reads them); writes
runs/s72/val-line.csv and val-side.csv. Run from the repository root."""
import csv

import numpy as np

from model.draem.checkpoint import load_checkpoint
from station.datasets import judged_part_of
from station.evaluation import evaluate_tensors, inference_net, model_split, without_held_out_type
from station.presence import PresenceCheck

for name, model, data, rule in (("line", "model/weights/default", "data/line-pv-val", "dolp_contrast"),
                                ("side", "runs/make-side-model/side", "data/sw-pv-val", "row_contrast")):
    ck = load_checkpoint(model)
    sp, _ = judged_part_of(model_split(ck, model, data, "val", presence=PresenceCheck(rule=rule)))
    sp = without_held_out_type(sp, ck.meta.get("train", {}))
    _, ev = evaluate_tensors(inference_net(ck, model, "fp32"), sp)
    with open(f"runs/s72/val-{name}.csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["index", "label", "defect_type", "score"])
        for row in zip(sp.index, sp.label.numpy().tolist(), sp.defect_type, np.asarray(ev.scores).tolist(),
                       strict=True):
            w.writerow(row)
    print(name, "done", flush=True)
