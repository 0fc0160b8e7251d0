"""Save the shipped variation model's maps and scores on the validation set (for where.py and mass.py).
Usage: PYTHONPATH=. python argmax.py OUT.npz"""

import sys

import numpy as np
from common import load_val

vm, x, lab, types, index = load_val()
outs = [vm.zmaps(x[i:i + 50]) for i in range(0, len(x), 50)]
maps = np.concatenate([o.maps.numpy() for o in outs])
np.savez_compressed(sys.argv[1], maps=maps.astype(np.float16), scores=np.concatenate([o.scores.numpy() for o in outs]),
                    label=lab, types=types, index=index, region=vm.scored_region(), reference=vm.reference.numpy())
