"""station's command line with the variation model's AoLP features as (S1, S2) / median S0 over the part region
instead of (S1, S2) / S0 (screen only: the file does not record it, so fit and score through this wrapper).

    python patched.py variation --model runs/c73/repro/src/default --refit --data data/line-pf-train \
        --val-data data/line-pf-val --decision variation --out runs/s74/Pv
    python patched.py eval --model runs/s74/Pv --data data/line-pv-val --split val --no-synthetic --no-plots ...
"""
import sys

import numpy as np

from model.draem import variation as v

_features = v.VariationModel.features


def features(self: v.VariationModel, x: np.ndarray, region: np.ndarray | None = None) -> np.ndarray:
    f = _features(self, x, region)
    if self.aolp is not None:
        i = np.maximum(np.nan_to_num(np.asarray(x[self.intensity], np.float32)), v.LOG_FLOOR)
        reg = self.region.numpy() if region is None else region
        f[self.aolp:self.aolp + 2] *= i / (np.median(i[reg]) if reg.any() else np.median(i))
    return f


v.VariationModel.features = features
from station.cli import main  # noqa: E402

sys.exit(main(sys.argv[1:]))
