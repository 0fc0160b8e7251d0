"""Backpressure policies: every drop is reported, nothing vanishes, nobody waits forever."""

from __future__ import annotations

import threading
import time

import pytest

from station.frame_queue import Closed, FrameQueue


def test_drop_oldest_evicts_and_reports_the_oldest():
    q = FrameQueue[int](2, "drop_oldest")
    assert q.put(1) == [] and q.put(2) == []
    assert q.put(3) == [1]
    assert [q.get(0), q.get(0)] == [2, 3] and q.dropped == 1


def test_drop_newest_refuses_the_new_item():
    q = FrameQueue[int](2, "drop_newest")
    q.put(1)
    q.put(2)
    assert q.put(3) == [3]
    assert [q.get(0), q.get(0), q.get(0)] == [1, 2, None]


def test_block_waits_for_room_then_refuses_after_its_timeout():
    q = FrameQueue[int](1, "block", block_timeout_s=0.2)
    q.put(1)
    threading.Timer(0.05, q.get).start()
    assert q.put(2) == []  # room was made by the consumer
    t = time.monotonic()
    assert q.put(3) == [3]  # nobody consumed: refused after the timeout, not lost silently
    assert 0.15 < time.monotonic() - t < 2


def test_every_item_is_either_consumed_or_reported_dropped_under_load():
    q = FrameQueue[int](3, "drop_oldest")
    dropped: list[int] = []
    got: list[int] = []

    def consume():
        while True:
            try:
                item = q.get(timeout_s=1)
            except Closed:
                return
            if item is not None:
                got.append(item)
                time.sleep(0.0005)

    t = threading.Thread(target=consume)
    t.start()
    for i in range(2000):
        dropped += q.put(i)
    q.close()
    t.join(5)
    assert sorted(got + dropped) == list(range(2000))
    assert dropped and got


def test_close_wakes_consumers_and_refuses_producers():
    q = FrameQueue[int](2)
    q.put(7)
    q.close()
    assert q.get(0) == 7
    with pytest.raises(Closed):
        q.get(1)
    with pytest.raises(Closed):
        q.put(8)


@pytest.mark.parametrize(("size", "policy"), [(0, "block"), (2, "random")])
def test_bad_settings(size, policy):
    with pytest.raises(ValueError):
        FrameQueue(size, policy)
