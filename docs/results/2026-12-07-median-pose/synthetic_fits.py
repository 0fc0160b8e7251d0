"""The unit tests' synthetic parts (tests/model/test_variation.py), fitted with the reference started from the first
part (as before this stop) and from the part nearest the median pose (``median_part``): four fit seeds, plain parts and
parts with a mottled end, each fit read on 100 new good parts of the fixture's play (2 px). Prints per fit the good
parts' RMS of registered intensity against the reference (median, 95th percentile, highest) and their scores (highest
and 95th percentile). Run from the repository's root at commit 62001ae5, the change (``median_part``; reverted in
480b4cee): ``PYTHONPATH=.:tests/model python synthetic_fits.py``; its output is synthetic_fits.txt."""

import numpy as np
import torch
from test_variation import H, W, mottled, noisier, parts

from model.draem.variation import VariationModel


def rms(vm: VariationModel, good: torch.Tensor) -> np.ndarray:
    """Each good part's RMS of registered intensity feature less the reference, over the region."""
    ref, region = vm.reference.numpy(), vm.region.numpy()
    return np.array([float(np.sqrt(np.mean((vm._aligned(g)[0][vm.intensity] - ref)[region] ** 2)))
                     for g in good.numpy()])


for kind in ("plain", "mottled"):
    for seed in range(4):
        fit, good = parts(60, seed), parts(100, 50 + seed)
        if kind == "mottled":
            fit, good = mottled(noisier(fit, seed, 0.01), seed), mottled(noisier(good, 50 + seed, 0.01), 50 + seed)
        row = []
        for start in ("first part", "median part"):
            vm = VariationModel(4, (H, W), intensity=0)
            if start == "first part":
                vm.median_part = lambda feats: 0  # type: ignore[method-assign]
            vm.fit(fit, fit[:, 0] > 0.15)
            e, s = rms(vm, good), vm.zmaps(good).scores.numpy()
            row.append(f"{start}: RMS median {np.median(e):.3f}, p95 {np.percentile(e, 95):.3f}, highest "
                       f"{e.max():.3f}; score highest {s.max():.1f}, p95 {np.percentile(s, 95):.1f}")
        print(f"{kind}, fit seed {seed}: " + " | ".join(row), flush=True)
