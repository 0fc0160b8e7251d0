"""Why rule 42's X lost scratches (a diagnosis after the decision; it decides nothing): the image AUROC of dents and
scratches for each screened fit, on the validation set and on seed 1141 (which decided rule 42), to tell which of
X's three parts (contrast divided out: M; clusters: L, ML; blurred copies: MB, MLB) costs them.
Usage (repository root): python docs/results/2026-11-28-contrast-mean/why/why.py"""

from __future__ import annotations

import numpy as np
from sklearn.metrics import roc_auc_score

from model.draem.checkpoint import load_checkpoint
from station.evaluation import model_split

MODELS = {"C": "model/weights/default", "L": "runs/r40/L", "M": "runs/r42/M", "ML": "runs/r42/ML", "MB": "runs/r42/MB",
          "MLB": "runs/r42/MLB"}
SETS = {"validation": ("data/line-panel-val", "val"), "seed 1141": ("data/line-panel-heldout-1141", "test")}
TYPES = ("all", "dent", "scratch")


def main() -> None:
    cks = {k: load_checkpoint(v) for k, v in MODELS.items()}
    print("| set | model | " + " | ".join(TYPES) + " |\n|---|---|" + "---|" * len(TYPES))
    for set_name, (data, split) in SETS.items():
        sp = model_split(cks["C"], MODELS["C"], data, split)
        y = np.asarray(sp.label) == 1
        kind = np.asarray(sp.defect_type)
        for name, ck in cks.items():
            s = ck.detector.variation.zmaps(sp.priors).scores.numpy()
            cells = []
            for t in TYPES:
                keep = ~y | (kind == t) if t != "all" else np.ones_like(y)
                cells.append(f"{roc_auc_score(y[keep], s[keep]):.3f}")
            print(f"| {set_name} | {name} | " + " | ".join(cells) + " |", flush=True)


if __name__ == "__main__":
    main()
