"""Rule 41's K: the contrast gain of seed 1140's good parts, as shot and through a gamma of 1.25, against the good
training parts' range that K recorded. Usage (repository root, after models.sh): python .../why/why.py"""

from __future__ import annotations

import numpy as np
import torch

from model.draem.checkpoint import load_checkpoint
from model.draem.shifts import Channels, shift
from station.evaluation import model_split


def main() -> None:
    ck = load_checkpoint("runs/r41/K")
    vm = ck.detector.variation
    sp = model_split(ck, "runs/r41/K", "data/line-panel-heldout-1140", "test", good_only=True)
    lo, hi = (float(v) for v in vm.contrast_range)
    print(f"K's range (376 good training parts): {lo:.3f} - {hi:.3f}\n\n| frames | contrast gain p10 / p50 / p90 | "
          f"beyond the range |\n|---|---|---|")
    for name in ("none", "gamma 1.25", "gamma 0.8"):
        x = torch.from_numpy(shift(name, sp.priors.numpy(), Channels.of(ck.detector.config.priors)))
        cs = []
        for xi in x.numpy():
            warped, _, where = vm._aligned(xi)
            cs.append(vm.contrast_factor(warped[:-1], where))
        cs = np.array(cs)
        print(f"| {len(cs)} good parts, {name} | {np.percentile(cs, 10):.3f} / {np.median(cs):.3f} / "
              f"{np.percentile(cs, 90):.3f} | {100 * np.mean((cs < lo) | (cs > hi)):.0f} % |")


if __name__ == "__main__":
    main()
