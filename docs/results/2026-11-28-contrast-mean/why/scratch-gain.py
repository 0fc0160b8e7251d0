"""Where do scratches lose when the contrast is divided out (after rule 42; decides nothing)? On seed 1141, for the
good parts and each defect type: the median contrast gain c the M fit (runs/r42/M, contrast divided out) measures,
and the variation score of C (the shipped file) and of M, each in units of its own good parts' scores (median and
1.4826 MAD), so the two are comparable: the median, and the 10th percentile (defective) or 90th (good), where the
classes overlap. Then the rank correlation, over the good parts and over the scratched ones, of the change of
score from C to M with log c (dividing the log intensity by c scales its noise by 1 / c), and the ten good parts M
scores highest. Usage (repository root): python .../why/scratch-gain.py"""

from __future__ import annotations

import numpy as np
from scipy.stats import spearmanr

from model.draem.checkpoint import load_checkpoint
from station.evaluation import model_split

MODELS = {"C": "model/weights/default", "M": "runs/r42/M"}


def main() -> None:
    cks = {k: load_checkpoint(v) for k, v in MODELS.items()}
    sp = model_split(cks["C"], MODELS["C"], "data/line-panel-heldout-1141", "test")
    kind = np.array([t or "good" for t in sp.defect_type])
    vm = cks["M"].detector.variation
    gains = []
    for xi in sp.priors.float().numpy():
        warped, _, where = vm._aligned(xi)
        gains.append(vm.contrast_factor(warped[:-1], where))
    gains = np.array(gains)
    z = {}
    for name, ck in cks.items():
        s = ck.detector.variation.zmaps(sp.priors).scores.numpy()
        g = s[kind == "good"]
        z[name] = (s - np.median(g)) / (1.4826 * np.median(np.abs(g - np.median(g))))
    print("| seed 1141 | parts | gain c: median (10-90 %) | score C: median, tail | score M: median, tail |\n"
          "|---|---|---|---|---|")
    for t in ["good", *sorted(set(kind) - {"good"})]:
        k = kind == t
        lo, mid, hi = np.percentile(gains[k], [10, 50, 90])
        q = 90 if t == "good" else 10
        cells = [f"{np.median(z[m][k]):.1f}, {np.percentile(z[m][k], q):.1f}" for m in MODELS]
        print(f"| {t} | {int(k.sum())} | {mid:.3f} ({lo:.3f}-{hi:.3f}) | " + " | ".join(cells) + " |")
    change, log_c = z["M"] - z["C"], np.log(gains)
    print("\nRank correlation of the score's change (M - C) with log c: " + ", ".join(
        f"{t} {spearmanr(change[kind == t], log_c[kind == t])[0]:+.2f}" for t in ("good", "scratch")))
    good = kind == "good"
    top = np.argsort(z["M"][good])[-10:]
    print("The ten good parts M scores highest: c " + " ".join(f"{v:.2f}" for v in gains[good][top])
          + "; C's score " + " ".join(f"{v:.1f}" for v in z["C"][good][top])
          + "; M's " + " ".join(f"{v:.1f}" for v in z["M"][good][top]))


if __name__ == "__main__":
    main()
