"""Screen for rule 42 (validation set only; it decides nothing): fits that divide every frame's contrast gain out,
their own good parts' too (``station variation --global-contrast mean``), without clusters (M) and with 8 (ML), and
both again with blurred copies of the good parts (``--blur-copies 1.5``: MB, MLB), against the shipped file (C) and
rule 40's clustered fit (L), on the validation set's parts as shot and shifted: image AUROC, and good parts rejected
at the threshold that rejects 5 % of the unshifted good parts. "L, scale >= 1" and "ML, scale >= 1": the clustered
files with each cluster's residual scale floored at the global one (1 in these units) at test time only, so a
cluster can loosen the judgement but never tighten it. Usage (repository root, after the fits in models.sh):
python docs/results/2026-11-28-contrast-mean/screen.py"""

from __future__ import annotations

import numpy as np
import torch
from sklearn.metrics import roc_auc_score

from model.draem.checkpoint import load_checkpoint
from model.draem.shifts import Channels, shift
from station.evaluation import model_split

MODELS = {"C": "model/weights/default", "L": "runs/r40/L", "M": "runs/r42/M", "ML": "runs/r42/ML", "MB": "runs/r42/MB",
          "MLB": "runs/r42/MLB"}
SHIFTS = ("none", "gamma 1.25", "gamma 0.8", "dolp x0.5", "blur 1 px", "blur 0.5 px", "rotate 5 deg")


def main() -> None:
    cks = {k: load_checkpoint(v) for k, v in MODELS.items()}
    va = model_split(cks["C"], MODELS["C"], "data/line-panel-val", "val")
    y = np.asarray(va.label) == 1
    ch = Channels.of(cks["C"].detector.config.priors)
    shifted = {n: torch.from_numpy(shift(n, va.priors.numpy(), ch)) for n in SHIFTS}
    print("| model | AUROC as shot | " + " | ".join(f"{n}: AUROC, good rejected" for n in SHIFTS[1:]) + " |\n"
          "|---|---|" + "---|" * (len(SHIFTS) - 1))
    for name in [*MODELS, "L, scale >= 1", "ML, scale >= 1"]:
        vm = cks[name.split(",")[0]].detector.variation
        if "scale" in name:
            vm.cluster_scale.clamp_(min=1.0)
        s = {n: vm.zmaps(x).scores.numpy() for n, x in shifted.items()}
        thr = np.quantile(s["none"][~y], 0.95)
        cells = [f"{roc_auc_score(y, s['none']):.3f}"]
        cells += [f"{roc_auc_score(y, s[n]):.3f}, {100 * np.mean(s[n][~y] > thr):.0f} %" for n in SHIFTS[1:]]
        print(f"| {name} | " + " | ".join(cells) + " |", flush=True)


if __name__ == "__main__":
    main()
