"""Re-expose a rendered set through a lens as ../2026-11-29-sensor-optics/resensor.py does (KIND blur or all), with
the render's fireflies first brought to full scale as ``sim.sensor.lens_blur`` now does (``suppress_fireflies``).
resensor.py blurs first in its chain, and the suppression changes only firefly pixels, so this is its chain with the
suppression in front of the blur.

    PYTHONPATH=. python reexpose.py SRC DST KIND"""
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent.parent / "2026-11-29-sensor-optics"))
import resensor

from sim.sensor import suppress_fireflies

unsuppressed = resensor.mosaic


def mosaic(s0, s1, s2, layout, kind, pat):
    assert kind in ("blur", "all"), kind
    return unsuppressed(*suppress_fireflies(s0, s1, s2), layout, kind, pat)


resensor.mosaic = mosaic
resensor.main(Path(sys.argv[1]), Path(sys.argv[2]), sys.argv[3])
