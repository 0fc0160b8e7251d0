"""Cache each validation part's max-channel z map before the window (after clusters and the frame's noise level),
its root chi-square over the channels, its signed z (``signed_z``) and its judged pixels. For lines.py.
Usage: PYTHONPATH=. python lines_cache.py OUT.npz"""
import sys

import numpy as np
from common import load_val

from model.draem.variation import NOISE_CAP

vm, x, lab, types, index = load_val()
zs, chi, js, signed = [], [], [], []
for xi in x.numpy():
    r, coef, judged, _ = vm._judged_residual(xi)
    r = vm.clustered(r, coef)
    z = np.abs(r)
    level = vm.noise_level(vm.used(z), judged)
    z = z / (level if 1.0 < level <= NOISE_CAP else 1.0)
    zs.append(z.max(0).astype(np.float32))
    chi.append(np.sqrt((vm.used(z) ** 2).sum(0)).astype(np.float32))
    js.append(judged)
    signed.append(vm.used(vm.signed_z(r, judged, level)).astype(np.float16))
np.savez_compressed(sys.argv[1], z=np.stack(zs), chi=np.stack(chi), signed=np.stack(signed), judged=np.stack(js),
                    label=lab, types=types,
                    index=index, region=vm.scored_region(), box=vm.box_px)
print("cached", len(zs))
