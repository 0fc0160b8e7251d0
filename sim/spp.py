"""Samples per pixel from a target DoLP error, using the error curve that ``station bench render`` measured.

The curve (``SPP_TABLE``, JSON) holds, per spp, the DoLP RMSE of a 640x480 render on object pixels against a
high-spp reference of the same scene, the reference's own noise removed in quadrature (see
``station.benchmarks.render``). It was measured with this renderer (``RENDERER_VERSION``) on the project's
machine; ``station bench render --write-table sim/spp_table.json`` re-measures it. Between measured points the
error is interpolated linearly in log(spp)-log(error) (Monte Carlo noise falls as a power of spp).
"""

from __future__ import annotations

import json
import logging
import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from .errors import SimError
from .render import RENDERER_VERSION
from .scene import sampler_spp

log = logging.getLogger(__name__)

SPP_TABLE = Path(__file__).with_name("spp_table.json")


@dataclass(frozen=True)
class SppChoice:
    """The chosen ``spp``, the error the curve predicts for it, and where the curve came from."""

    spp: int
    dolp_error_target: float
    predicted_dolp_error: float
    table: str
    measured: str

    def to_dict(self) -> dict[str, Any]:
        return {"dolp_error_target": self.dolp_error_target, "spp": self.spp,
                "predicted_dolp_error": round(self.predicted_dolp_error, 5), "table": self.table,
                "measured": self.measured}


def load_table(path: str | Path = SPP_TABLE) -> dict[str, Any]:
    """Read and check an spp table (JSON with ``renderer_version`` and ``points``: [{spp, dolp_rmse}])."""
    path = Path(path)
    try:
        table = json.loads(path.read_text())
        points = [(int(p["spp"]), float(p["dolp_rmse"])) for p in table["points"]]
    except (OSError, json.JSONDecodeError, KeyError, TypeError, ValueError) as exc:
        raise SimError(f"spp table {path}: unreadable ({exc})") from None
    if table.get("renderer_version") != RENDERER_VERSION:
        raise SimError(f"spp table {path} was measured with renderer version {table.get('renderer_version')}, this "
                       f"code renders version {RENDERER_VERSION}: re-measure it with "
                       f"`station bench render --write-table {path}`")
    if len(points) < 2 or any(s < 1 or not e > 0 for s, e in points) or len({s for s, _ in points}) != len(points):
        raise SimError(f"spp table {path}: need >= 2 points with distinct spp >= 1 and errors > 0")
    return table


def spp_for_dolp_error(target: float, width: int = 640, height: int = 480, path: str | Path = SPP_TABLE
                       ) -> SppChoice:
    """The smallest spp whose DoLP RMSE on the measured curve is <= ``target`` (DoLP is a fraction in [0, 1]).

    Raises SimError when the target is below the smallest error measured (no extrapolation beyond the curve).
    The error is per pixel, so it carries over to other image sizes only roughly (logged)."""
    if not (math.isfinite(target) and 0 < target < 1):
        raise SimError(f"--dolp-error must be in (0, 1) (DoLP RMSE), got {target}")
    table = load_table(path)
    pts = sorted((int(p["spp"]), float(p["dolp_rmse"])) for p in table["points"])
    spp = np.array([s for s, _ in pts], dtype=np.float64)
    # more samples never make it worse: the measured curve's wiggles (a few scenes) are flattened
    err = np.minimum.accumulate(np.array([e for _, e in pts], dtype=np.float64))
    if (width, height) != (table.get("width"), table.get("height")):
        log.warning("spp table %s was measured at %sx%s, not %dx%d: the chosen spp is approximate", path,
                    table.get("width"), table.get("height"), width, height)
    measured = str(table.get("measured", ""))
    if target >= err[0]:
        return SppChoice(int(spp[0]), target, float(err[0]), str(path), measured)
    if target < err[-1]:
        raise SimError(f"--dolp-error {target}: below the smallest DoLP error measured ({err[-1]:.4f} at "
                       f"{int(spp[-1])} spp, {path}); use --spp, or extend the curve with station bench render "
                       f"--spp ... --write-table")
    k = int(np.argmax(err <= target))  # first measured point that meets the target; k >= 1 here
    s0, s1, e0, e1 = spp[k - 1], spp[k], err[k - 1], err[k]
    if e1 == e0:
        return SppChoice(int(s1), target, float(e1), str(path), measured)

    def curve(n: int) -> float:
        return math.exp(math.log(e0) + (math.log(e1) - math.log(e0)) * (math.log(n) - math.log(s0)) / (
            math.log(s1) - math.log(s0)))

    # only counts the sampler takes as they are (sampler_spp), so that the manifest's spp is what is rendered
    chosen = next(n for n in range(int(s0) + 1, int(s1) + 1)
                  if sampler_spp(n) == n and (curve(n) <= target * (1 + 1e-9) or n == int(s1)))
    return SppChoice(chosen, target, curve(chosen), str(path), measured)
