"""A bounded hand-over queue between threads with an explicit backpressure policy that reports every drop.

drop_oldest  a full queue evicts its oldest item to take the new one (the line keeps moving, freshest parts win)
drop_newest  a full queue refuses the new item
block        the producer waits for room (up to ``block_timeout_s``; then the new item is refused)

``put`` returns the items that were dropped so the caller can log each as not inspected: nothing vanishes.
"""

from __future__ import annotations

import collections
import threading
from typing import Generic, TypeVar

T = TypeVar("T")
POLICIES = ("drop_oldest", "drop_newest", "block")


class Closed(Exception):
    """The queue was closed; producers stop putting, consumers stop after draining."""


class FrameQueue(Generic[T]):
    def __init__(self, maxsize: int, policy: str = "drop_oldest", block_timeout_s: float = 5.0) -> None:
        if maxsize < 1:
            raise ValueError(f"queue size must be >= 1, got {maxsize}")
        if policy not in POLICIES:
            raise ValueError(f"backpressure policy must be one of {POLICIES}, got {policy!r}")
        self.maxsize, self.policy, self.block_timeout_s = maxsize, policy, block_timeout_s
        self._items: collections.deque[T] = collections.deque()
        self._cond = threading.Condition()
        self._closed = False
        self.dropped = 0

    def put(self, item: T) -> list[T]:
        """Add ``item``; return what was dropped to make room or refused (empty when nothing was)."""
        with self._cond:
            if self._closed:
                raise Closed("put on a closed queue")
            dropped: list[T] = []
            if len(self._items) >= self.maxsize:
                if self.policy == "drop_oldest":
                    dropped.append(self._items.popleft())
                elif self.policy == "drop_newest":
                    dropped.append(item)
                elif not self._cond.wait_for(lambda: len(self._items) < self.maxsize or self._closed,
                                             timeout=self.block_timeout_s) or self._closed:
                    dropped.append(item)
            if not dropped or dropped[0] is not item:
                self._items.append(item)
                self._cond.notify_all()
            self.dropped += len(dropped)
            return dropped

    def get(self, timeout_s: float | None = None) -> T | None:
        """The oldest item; None on timeout. Raises Closed once the queue is closed and empty."""
        with self._cond:
            if not self._cond.wait_for(lambda: self._items or self._closed, timeout=timeout_s):
                return None
            if self._items:
                item = self._items.popleft()
                self._cond.notify_all()
                return item
            raise Closed("queue closed")

    def close(self) -> None:
        """Wake every waiter; remaining items can still be drained with ``get``."""
        with self._cond:
            self._closed = True
            self._cond.notify_all()

    def __len__(self) -> int:
        with self._cond:
            return len(self._items)
