"""Why rule 40's clustered fit L rejects good parts under frame-wide shifts: for seed 1139's good parts, shifted as
`station bench shift` shifts them, each model's frame noise level (median z / 0.6745 over the part; divided out
between 1 and NOISE_CAP = 3) and score, and L's distance to its nearest cluster (1 = a typical good training part).
Usage (repository root, after models.sh): python docs/results/2026-11-28-appearance-clusters/why/why.py"""

from __future__ import annotations

import numpy as np
import torch

from model.draem.checkpoint import load_checkpoint
from model.draem.shifts import Channels, shift
from station.evaluation import model_split

MODELS = {"C": "model/weights/default", "L": "runs/r40/L"}
SHIFTS = ("none", "gamma 1.25", "dolp x0.5", "blur 1 px")


def main() -> None:
    cks = {k: load_checkpoint(v) for k, v in MODELS.items()}
    sp = model_split(cks["C"], MODELS["C"], "data/line-panel-heldout-1139", "test", good_only=True)
    ch = Channels.of(cks["C"].detector.config.priors)
    lm = cks["L"].detector.variation
    print("| shift | model | threshold | good rejected | noise level p50 / p90 | above the cap (3) | L: distance to "
          "nearest cluster p50 / p90 |\n|---|---|---|---|---|---|---|")
    for name in SHIFTS:
        x = torch.from_numpy(shift(name, sp.priors.numpy(), ch))
        d = []
        for xi in x.numpy():
            coef = lm._judged_residual(xi)[1] / lm.cluster_spread.numpy()
            d.append(float(np.sqrt(((coef[None] - lm.cluster_centres.numpy()) ** 2).sum(1).min())))
        for k, ck in cks.items():
            out = ck.detector.variation.zmaps(x)
            score = ck.detector.predict(x).score.numpy()
            lv = out.noise_level.numpy()
            dist = f"{np.median(d):.2f} / {np.percentile(d, 90):.2f}" if k == "L" else ""
            print(f"| {name} | {k} | {ck.threshold:.3f} | {100 * np.mean(score > ck.threshold):.1f} % | "
                  f"{np.median(lv):.2f} / {np.percentile(lv, 90):.2f} | {100 * np.mean(lv > 3):.0f} % | {dist} |",
                  flush=True)


if __name__ == "__main__":
    main()
