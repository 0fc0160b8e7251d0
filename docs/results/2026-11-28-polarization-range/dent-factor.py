"""Does a dent pull the frame-wide polarization factor k of rule 37's B? For the seed-1133 dents B lost most (and a
few other parts), k fitted over the judged pixels with and without the defect's registered mask.
Usage (repository root, after rule 37's models.sh made runs/gp/B):
    python docs/results/2026-11-28-polarization-range/dent-factor.py data/line-panel-heldout-1133 70,19,148,...
"""

from __future__ import annotations

import sys

import numpy as np

from model.draem.checkpoint import load_checkpoint
from station.evaluation import model_split


def main() -> None:
    ck = load_checkpoint("runs/gp/B")
    vm = ck.detector.variation
    sp = model_split(ck, "runs/gp/B", sys.argv[1], "test")
    mean, part = vm.mean.numpy(), vm.region.numpy()
    where = {ix: i for i, ix in enumerate(sp.index)}
    print("| part | type | defect px judged | judged px | k with them | k without |\n|---|---|---|---|---|---|")
    for ix in (int(a) for a in sys.argv[2].split(",")):
        i = where[ix]
        xi = sp.priors[i].float().numpy()
        warped = vm.register(xi, vm.features(xi))
        judged = part & ~vm.highlight(warped[-1])
        dm = vm.register_masks(sp.priors[i:i + 1], sp.defect_mask[i:i + 1].bool())[0].numpy()
        k_all = vm.polarization_factor(warped[:-1], mean, judged)
        k_wo = vm.polarization_factor(warped[:-1], mean, judged & ~dm)
        fmt = lambda k: f"{abs(k):.3f} at {np.degrees(np.angle(k)) / 2:+.2f} deg"  # noqa: E731
        print(f"| {ix} | {sp.defect_type[i] or 'good'} | {int((dm & judged).sum())} | {int(judged.sum())} | "
              f"{fmt(k_all)} | {fmt(k_wo)} |")


if __name__ == "__main__":
    main()
