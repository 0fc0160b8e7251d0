"""After rule 42 (it decides nothing): does the residual in the frame's own units win back the scratches X lost?
Image AUROC of all defects, dents and scratches on seed 1141 (which decided rule 42 and so may be looked at now) for
the shipped file C, X (MLB, scored with the new code) and MLBN (fitted with it). Usage (repository root):
python .../check-1141.py"""

from __future__ import annotations

import numpy as np
from sklearn.metrics import roc_auc_score

from model.draem.checkpoint import load_checkpoint
from station.evaluation import model_split

MODELS = {"C": "model/weights/default", "MLB (scored with the patch)": "runs/r42/MLB", "MLBN": "runs/r43/MLBN"}


def main() -> None:
    cks = {k: load_checkpoint(v) for k, v in MODELS.items()}
    sp = model_split(cks["C"], MODELS["C"], "data/line-panel-heldout-1141", "test")
    y, kind = np.asarray(sp.label) == 1, np.asarray(sp.defect_type)
    print("| seed 1141 | all | dents | scratches |\n|---|---|---|---|")
    for name, ck in cks.items():
        s = ck.detector.variation.zmaps(sp.priors).scores.numpy()
        cells = [f"{roc_auc_score(y, s):.3f}"]
        cells += [f"{roc_auc_score(y[~y | (kind == t)], s[~y | (kind == t)]):.3f}" for t in ("dent", "scratch")]
        print(f"| {name} | " + " | ".join(cells) + " |", flush=True)


if __name__ == "__main__":
    main()
