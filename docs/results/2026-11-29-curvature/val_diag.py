"""Rule 59 amendment's check: each fit's variation scores on data/line-pv-val, the window alone (no second look) and
as the file scores (with it); caught at 1 % of the set's own good parts. Usage: python val_diag.py MODEL..."""
import sys

import numpy as np
import torch

from model.draem.checkpoint import load_checkpoint
from model.draem.metrics import auroc
from model.draem.second_look import SecondLook
from station.evaluation import model_split

for m in sys.argv[1:]:
    ck = load_checkpoint(m)
    vm = ck.detector.variation
    s = model_split(ck, m, "data/line-pv-val", "val")
    y, t = np.asarray(s.label), np.array(s.defect_type)
    with torch.no_grad():
        full = vm.zmaps(s.priors).scores.numpy()
        vm.second_look = SecondLook()
        win = vm.zmaps(s.priors).scores.numpy()
    for name, sc in (("window", win), ("with look", full)):
        th = np.percentile(sc[y == 0], 99)
        print(m, name, f"auroc {auroc(y, sc):.3f} caught@1% {(sc[y == 1] > th).mean():.3f} "
              f"dents {(sc[t == 'dent'] > th).mean():.3f}", flush=True)
