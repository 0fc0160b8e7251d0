"""Argument types shared by the commands: each turns a bad value into argparse's one-line error naming the flag."""

from __future__ import annotations

import argparse
import math
from collections.abc import Callable

from model.draem.config import GOOD_REJECTED_RATE
from station.config import MAX_SEED, PRESENCE_RULES


def _integer(text: str) -> int:
    try:
        return int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not an integer") from None


def seed(text: str) -> int:
    """A seed: an integer in 0..``MAX_SEED``."""
    value = _integer(text)
    if not 0 <= value <= MAX_SEED:
        raise argparse.ArgumentTypeError(f"{value} is outside 0..2**63-1")
    return value


def _positive_number(text: str, unit: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a number") from None
    if not (math.isfinite(value) and value > 0):
        raise argparse.ArgumentTypeError(f"{text!r}: a number of {unit} > 0")
    return value


def positive_seconds(text: str) -> float:
    """A duration in seconds: a finite number > 0."""
    return _positive_number(text, "seconds")


def positive_int(text: str) -> int:
    """A count or size: an integer >= 1."""
    value = _integer(text)
    if value < 1:
        raise argparse.ArgumentTypeError(f"{value}: must be >= 1")
    return value


def even_size(text: str) -> int:
    """An image side in pixels: an even integer >= 2 (whole 2x2 polarizer superpixels)."""
    value = positive_int(text)
    if value % 2:
        raise argparse.ArgumentTypeError(f"{value}: must be even (whole 2x2 polarizer superpixels)")
    return value


def positive_minutes(text: str) -> float:
    """A time budget in minutes: a finite number > 0."""
    return _positive_number(text, "minutes")


def path_text(text: str) -> str:
    """A file or folder path: not empty (an empty path means the working directory to most code, never meant)."""
    if not text.strip():
        raise argparse.ArgumentTypeError("empty: give a path")
    return text


def number_range(flag: str, example: str) -> Callable[[str], tuple[float, float]]:
    """An argument type for ``flag``: ``X`` -> (X, X), ``LO,HI`` -> (LO, HI), floats; ``example`` completes the error
    ("must be X or LO,HI in <example>"). Range checks are the caller's."""
    def parse(text: str) -> tuple[float, float]:
        try:
            values = [float(x) for x in text.split(",")]
        except ValueError:
            values = []
        if len(values) not in (1, 2):
            raise argparse.ArgumentTypeError(f"{flag} must be X or LO,HI in {example}, got {text!r}")
        return values[0], values[-1]
    return parse


def add_max_good_flagged(p: argparse.ArgumentParser, of: str = "the val split's good parts") -> None:
    """``--max-good-flagged``: the threshold rule's bound (default ``model.draem.config.GOOD_REJECTED_RATE``)."""
    p.add_argument("--max-good-flagged", type=float, default=GOOD_REJECTED_RATE,
                   help=f"threshold rule: at most this fraction of {of} rejected (default {GOOD_REJECTED_RATE})")


def add_presence_rule(p: argparse.ArgumentParser) -> None:
    """``--presence-rule``: the presence check that decides which frames the station would judge (``[presence]
    rule`` of the camera's station.toml; ``station.presence.PresenceRule``)."""
    p.add_argument("--presence-rule", default=PRESENCE_RULES[0], choices=PRESENCE_RULES,
                   help="the presence rule of the camera's station.toml [presence]: frames it calls empty are left "
                        "out (default dolp_contrast, a camera looking down at the belt; row_contrast for a camera "
                        "looking level at the part)")
