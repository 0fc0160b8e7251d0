"""The station's heap against the garbage collector's pauses (``station.heap``)."""

from __future__ import annotations

import gc

import pytest

from station.heap import frozen_heap


def test_the_heap_is_frozen_inside_and_unfrozen_after_even_on_error():
    kept = [[i] for i in range(1000)]
    with pytest.raises(RuntimeError), frozen_heap(long_ms=1e9) as pauses:
        assert gc.get_freeze_count() >= len(kept)
        raise RuntimeError("a run that fails")
    assert gc.get_freeze_count() == 0 and pauses not in gc.callbacks


def test_each_collection_is_counted_and_one_at_or_over_the_limit_counts_as_long():
    with frozen_heap(long_ms=0.0) as everything_long:
        gc.collect()
        gc.collect()
    with frozen_heap(long_ms=1e9) as nothing_long:
        gc.collect()
    assert everything_long.count == 2 and everything_long.long == 2 and everything_long.longest_ms > 0
    assert nothing_long.count == 1 and nothing_long.long == 0
