"""A screen for the rule after 40 (validation set only; it decides nothing): do rule 40's clusters hold under a gamma
and a halved DoLP when every frame's contrast is divided by all of its gain at test time (``contrast_range`` set to
(1, 1), as ``--global-polarization mean`` does for polarization)? For C (the shipped file) and L (runs/r40/L), on
the validation set's parts as shot and shifted: image AUROC, and good parts rejected at the threshold that rejects
5 % of the unshifted good parts. Usage (repository root, after rule 40's models.sh): python .../next/screen.py"""

from __future__ import annotations

import numpy as np
import torch
from sklearn.metrics import roc_auc_score

from model.draem.checkpoint import load_checkpoint
from model.draem.shifts import Channels, shift
from station.evaluation import model_split

MODELS = {"C": "model/weights/default", "L": "runs/r40/L"}
SHIFTS = ("none", "gamma 1.25", "dolp x0.5")


def main() -> None:
    cks = {k: load_checkpoint(v) for k, v in MODELS.items()}
    va = model_split(cks["C"], MODELS["C"], "data/line-panel-val", "val")
    y = (va.label == 1).numpy() if hasattr(va.label, "numpy") else np.asarray(va.label) == 1
    ch = Channels.of(cks["C"].detector.config.priors)
    shifted = {n: torch.from_numpy(shift(n, va.priors.numpy(), ch)) for n in SHIFTS}
    print("| model | contrast | AUROC as shot | gamma 1.25: AUROC, good rejected | DoLP x0.5: AUROC, good rejected |\n"
          "|---|---|---|---|---|")
    for name, ck in cks.items():
        vm = ck.detector.variation
        for contrast in ("as fitted", "all divided"):
            if contrast == "all divided":
                vm.contrast_range.copy_(torch.tensor([1.0, 1.0]))
            s = {n: vm.zmaps(x).scores.numpy() for n, x in shifted.items()}
            thr = np.quantile(s["none"][~y], 0.95)
            cells = [f"{roc_auc_score(y, s['none']):.3f}"]
            cells += [f"{roc_auc_score(y, s[n]):.3f}, {100 * np.mean(s[n][~y] > thr):.0f} %" for n in SHIFTS[1:]]
            print(f"| {name} | {contrast} | " + " | ".join(cells) + " |", flush=True)


if __name__ == "__main__":
    main()
