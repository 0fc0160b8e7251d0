"""Leave-one-type-out training sets (``--holdout-type T``): train without defect type T, evaluate on it.

Pure functions over per-sample defect types; good samples carry an empty type ("" or None) and always stay.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence

import numpy as np


def indices_without_type(types: Sequence[str | None], holdout: str | Iterable[str]) -> np.ndarray:
    """(M,) int64 indices, ascending, of the samples whose type is not held out.

    types: (N,) defect type per sample ("" or None for a good sample); holdout: one type or several. Raises
    ValueError when a held-out type names no sample (a misspelt type would otherwise hold out nothing and the
    "held-out" figure would be a trained-on one)."""
    held = {holdout} if isinstance(holdout, str) else set(holdout)
    if not held or "" in held:
        raise ValueError(f"holdout: name at least one defect type, got {sorted(held)}")
    names = np.array(["" if t is None else str(t) for t in types], dtype=object)
    missing = held - set(names.tolist())
    if missing:
        known = sorted(set(names.tolist()) - {""})
        raise ValueError(f"holdout: no sample of type {sorted(missing)} (types present: {known})")
    return np.flatnonzero(~np.isin(names, list(held))).astype(np.int64)


def learning_record(train: Mapping) -> Mapping:
    """The part of a checkpoint's sidecar record ``train`` that says what learned from rendered defects: its
    residual networks' (``train.residual``) when it has them, which then decide or look; else its networks'
    (``train.rendered_defects``); empty when nothing learned from a rendered defect."""
    return train.get("residual") or train.get("rendered_defects") or {}


def held_out_type(train: Mapping) -> str | None:
    """The defect type ``learning_record(train)`` says was left out; None when no type was held out."""
    return learning_record(train).get("holdout_type") or None


def learned_types(train: Mapping) -> tuple[str, ...] | None:
    """The defect types whose rendered parts ``learning_record(train)`` says were learned from, or None for a record
    that does not name them (records before 2026-12-01; their sets drew from the five default kinds at most)."""
    types = learning_record(train).get("types")
    return None if types is None else tuple(types)
