"""Screen after rule 42 (validation set only; it decides nothing): rule 42's X fitted again with the residual kept in
each frame's own units when its contrast is divided out (the divided residual times the gain, the frame against
the good parts' pattern scaled by it; ``VariationModel._judged_residual`` and ``fit`` since this screen), MLBN,
against the shipped file C and rule 42's MLB.
Image AUROC of all defects, dents and scratches as shot; image AUROC and good parts rejected at the threshold that
rejects 5 % of the unshifted good parts under each shift. MLB (least-squares division when fitted) is scored with
the new code. Usage (repository root): python docs/results/2026-11-28-contrast-mean/why/native-units/screen.py"""

from __future__ import annotations

import numpy as np
import torch
from sklearn.metrics import roc_auc_score

from model.draem.checkpoint import load_checkpoint
from model.draem.shifts import Channels, shift
from station.evaluation import model_split

MODELS = {"C": "model/weights/default", "MLB (scored with the patch)": "runs/r42/MLB", "MLBN": "runs/r43/MLBN"}
SHIFTS = ("none", "gamma 1.25", "gamma 0.8", "dolp x0.5", "blur 1 px", "rotate 5 deg")


def main() -> None:
    cks = {k: load_checkpoint(v) for k, v in MODELS.items()}
    va = model_split(cks["C"], MODELS["C"], "data/line-panel-val", "val")
    y = np.asarray(va.label) == 1
    kind = np.asarray(va.defect_type)
    ch = Channels.of(cks["C"].detector.config.priors)
    shifted = {n: torch.from_numpy(shift(n, va.priors.numpy(), ch)) for n in SHIFTS}
    print("| model | AUROC | dents | scratches | " + " | ".join(f"{n}: AUROC, good rejected" for n in SHIFTS[1:])
          + " |\n|---|---|---|---|" + "---|" * (len(SHIFTS) - 1))
    for name, ck in cks.items():
        s = {n: ck.detector.variation.zmaps(x).scores.numpy() for n, x in shifted.items()}
        thr = np.quantile(s["none"][~y], 0.95)
        cells = [f"{roc_auc_score(y, s['none']):.3f}"]
        for t in ("dent", "scratch"):
            keep = ~y | (kind == t)
            cells.append(f"{roc_auc_score(y[keep], s['none'][keep]):.3f}")
        cells += [f"{roc_auc_score(y, s[n]):.3f}, {100 * np.mean(s[n][~y] > thr):.0f} %" for n in SHIFTS[1:]]
        print(f"| {name} | " + " | ".join(cells) + " |", flush=True)


if __name__ == "__main__":
    main()
