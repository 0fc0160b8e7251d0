"""Before rule 43 (it decides nothing): does the robust gain win back the scratches rule 42's X lost on seed 1141?
Image AUROC of all defects, dents and scratches on seed 1141 (which decided rule 42 and so may be looked at now) for
the shipped file C and the robust-gain fits MR and MLBR. Run at commit 27843a6 (``robust_gain``, reverted after
this). Usage (repository root, at that commit): python .../check-1141.py"""

from __future__ import annotations

import numpy as np
from sklearn.metrics import roc_auc_score

from model.draem.checkpoint import load_checkpoint
from station.evaluation import model_split

MODELS = {"C": "model/weights/default", "MR": "runs/r43/MR", "MLBR": "runs/r43/MLBR"}


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
