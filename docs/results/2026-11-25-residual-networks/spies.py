"""Spies on the variation model for the cache scripts: after ``install()``, every ``VariationModel._residual`` call
appends its output (float32) to ``RES`` and every ``VariationModel.window`` call its judged pixels to ``JUD``."""

from __future__ import annotations

import numpy as np

from model.draem.variation import VariationModel

RES: list = []
JUD: list = []
_res, _win = VariationModel._residual, VariationModel.window


def res_spy(u, components, keep=None):
    r = _res(u, components, keep)
    RES.append(r.astype(np.float32))
    return r


def win_spy(self, z, judged):
    JUD.append(judged.copy())
    return _win(self, z, judged)


def install() -> None:
    VariationModel._residual = staticmethod(res_spy)
    VariationModel.window = win_spy
