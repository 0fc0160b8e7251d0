"""The station process's heap and Python's cyclic garbage collector.

A full collection walks every object the collector tracks and holds the interpreter while it does, so every thread
of the station stops with it. With the model, torch and the libraries loaded, the station's process tracks about
180,000 objects, and one full collection took 70-145 ms on these 2 cores with other work on them; with 3 million
objects alive it took 170-340 ms (docs/platform-facts.md). A part in flight then overruns a 100 ms cycle and is
rejected "not judged in time" (fail closed, but a good part lost). Those objects live as long as the station does.
``frozen_heap`` moves everything alive out of the collector's sight (``gc.freeze``) for the run; what the loop
allocates afterwards is still collected, quickly. ``collect`` is the one full collection before it, made before any
device is opened: a collection runs the finalizers of whatever garbage the process holds. Collecting inside the run,
after the PLC port had opened, hung the full test run twice (2026-11-29): the simulated PLC sent its triggers and
the station never received them, likeliest because a finalizer closed a file number the new pty had since taken.
``CollectorPauses`` records how long each collection held the process, so a run can say what its longest pause was.
"""

from __future__ import annotations

import contextlib
import gc
import time
from collections.abc import Iterator
from dataclasses import dataclass, field


@dataclass
class CollectorPauses:
    """The collector's pauses while watched (``gc.callbacks``): how many, the longest (ms), and how many reached
    ``long_ms``. The callback only records; the station reports (logging from inside a collection could wait on a
    lock that a stopped thread holds)."""

    long_ms: float
    count: int = 0
    longest_ms: float = 0.0
    long: int = 0
    _started: float = field(default=0.0, repr=False)

    def __call__(self, phase: str, info: dict[str, int]) -> None:
        if phase == "start":
            self._started = time.perf_counter()
            return
        ms = 1e3 * (time.perf_counter() - self._started)
        self.count += 1
        self.longest_ms = max(self.longest_ms, ms)
        self.long += ms >= self.long_ms


def collect() -> int:
    """One full collection, before the station opens its camera, PLC link and log (``station run``); the number of
    objects it found unreachable."""
    return gc.collect()


@contextlib.contextmanager
def frozen_heap(long_ms: float) -> Iterator[CollectorPauses]:
    """Freeze what is alive (``gc.freeze``; garbage not yet collected stays until the block ends) and watch the
    collector's pauses until the block ends; then unfreeze (the frozen objects return to the oldest generation, so a
    process that goes on, as a test session does, collects them again). ``long_ms``: the pause that counts as long
    (``CollectorPauses.long``)."""
    gc.freeze()
    pauses = CollectorPauses(long_ms)
    gc.callbacks.append(pauses)
    try:
        yield pauses
    finally:
        gc.callbacks.remove(pauses)
        gc.unfreeze()
