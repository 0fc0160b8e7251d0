"""The tall band's screen (plan.md): each arm's file on each set, as the station judges it.

Usage: python read.py B_FILE T_FILE SET:SPLIT ... (run from the repository's root). Prints per set and arm the good
parts rejected and by what (the window's score, the shape check's bend and the outline check's step, each over its
own threshold: above 1 rejects), the defective parts caught at the file's threshold per kind, and the share of parts
with some input pixel taken from outside the frame (``unseen_fraction > 0``); then each file's size."""

import os
import sys

import numpy as np

from model.draem.adapt import image_scores
from model.draem.checkpoint import load_checkpoint
from station.evaluation import model_split

files = {"B": sys.argv[1], "T": sys.argv[2]}
cks = {arm: load_checkpoint(path) for arm, path in files.items()}
for arm, path in files.items():
    print(f"{arm}: {path}, input {cks[arm].detector.config.input_shape}, threshold {cks[arm].threshold:.4f}, "
          f"{os.path.getsize(path + '.pt') / 1e6:.1f} MB")

for arg in sys.argv[3:]:
    path, split = arg.split(":")
    for arm, ck in cks.items():
        sp = model_split(ck, files[arm], path, split)
        x = sp.priors.float()
        lab = sp.label.numpy() == 1
        kinds = np.array([sp.defect_type[i] or "" for i in range(len(lab))])
        names = sorted(set(kinds[lab]))
        det, thr = ck.detector, ck.threshold
        s = image_scores(det, x)
        rej = s > thr
        out = det.variation.zmaps(x)
        unseen = out.unseen_fraction.numpy() > 0
        per = ", ".join(f"{k} {int(rej[lab & (kinds == k)].sum())}/{int((lab & (kinds == k)).sum())}" for k in names)
        caught = f"{int(rej[lab].sum())} of {int(lab.sum())} defective caught ({100 * rej[lab].mean():.1f} %; {per})" \
            if lab.any() else "no defective parts"
        print(f"\n{path}:{split} {arm}: {int(rej[~lab].sum())} of {int((~lab).sum())} good rejected; {caught}; "
              f"parts partly outside the view {int(unseen.sum())} of {len(lab)}", flush=True)
        for i in np.flatnonzero(rej & ~lab):
            print(f"  good part {int(i)}: score {s[i]:.4f}, window {float(out.scores[i]):.3f}, bend "
                  f"{float(out.edge_bend[i]):.3f}, step {float(out.edge_step[i]):.3f}, unseen "
                  f"{float(out.unseen_fraction[i]):.4f}")
        del x, out
