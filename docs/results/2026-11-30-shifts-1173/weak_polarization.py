"""Re-expose a rendered set with the scene's polarization halved before the polarizers (S1, S2 times 0.5: DoLP x0.5
as a renderer or a material that polarizes half as strongly would make it), through the set's own sensor draws,
clipping included. The physical counterpart of `station bench shift`'s "dolp x0.5", which halves DoLP after the
render clipped. Reuses check 54's re-exposure script (docs/results/2026-11-29-sensor-optics/resensor.py).

    PYTHONPATH=. python docs/results/2026-11-30-shifts-1173/weak_polarization.py SRC DST KIND   # KIND: none | dolp0.5
"""

import importlib.util
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[3]
spec = importlib.util.spec_from_file_location("resensor", ROOT / "docs/results/2026-11-29-sensor-optics/resensor.py")
resensor = importlib.util.module_from_spec(spec)
spec.loader.exec_module(resensor)
own_mosaic = resensor.mosaic


def mosaic(s0, s1, s2, layout, kind, pat):
    if kind == "dolp0.5":
        return own_mosaic(s0, 0.5 * s1, 0.5 * s2, layout, "none", pat)
    return own_mosaic(s0, s1, s2, layout, kind, pat)


resensor.mosaic = mosaic
resensor.KINDS = (*resensor.KINDS, "dolp0.5")

if __name__ == "__main__":
    resensor.main(Path(sys.argv[1]), Path(sys.argv[2]), sys.argv[3])
