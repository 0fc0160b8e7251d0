"""Screen: what do the appearance clusters group the good parts by? (stop 59)"""
import json
import sys

import numpy as np

from model.draem.checkpoint import load_checkpoint
from station.evaluation import model_split

model, data, out = sys.argv[1:4]
ck = load_checkpoint(model)
vm = ck.detector.variation
tr = model_split(ck, model, data, "train", good_only=True)
xs = tr.priors.numpy()
coefs = np.stack([vm._judged_residual(x)[1] for x in xs])
params = []
for i in tr.index:
    p = json.load(open(f"{data}/samples/{int(i):06d}/params.json"))
    s = p["scene"]
    params.append({"ring": s["ring_radiance"], "light": s["light"]["intensity"],
                   "yaw": s["pose"]["yaw_rad"], "alpha": s["materials"]["plastic"]["alpha"],
                   "finish": s["materials"]["plastic"]["finish"] == "smooth",
                   "lx": s["light"]["origin"][0], "ly": s["light"]["origin"][1],
                   "cx": s["camera"]["origin"][0],
                   "exposure": p["sensor"]["exposure_scale"] * p["sensor"]["exposure_gain"]})
np.savez(out, coefs=coefs, index=np.asarray(tr.index),
         **{k: np.array([q[k] for q in params], float) for k in params[0]})
print("saved", out, coefs.shape)
