"""The station's side of the PLC link: what the inspection loop needs from it (``LineLink``: announced parts in,
decisions out, acknowledgements back), and ``NoLink`` for trigger-free operation without a PLC.
``drivers.line_io.LineIO`` over a serial port (the simulated PLC included) implements ``LineLink``."""

from __future__ import annotations

from collections.abc import Callable
from typing import Protocol

from drivers.line_io import Trigger
from station.decision import Verdict


class LineLink(Protocol):
    """The station's side of the PLC link (``drivers.line_io.LineIO`` over a serial port, the simulated PLC
    included; ``NoLink`` without a PLC)."""

    triggered: bool
    """True: one part per PLC trigger; False: trigger-free, every frame is a part."""
    has_plc: bool
    """True: decisions go to a PLC that acknowledges them (``outcomes``); False: there is no one to tell."""

    def next_trigger(self, timeout_s: float) -> Trigger | None:
        """The oldest announced part not yet taken, or None when none arrived within ``timeout_s``."""
        ...

    def expired(self, before: float) -> list[Trigger]:
        """Take out the waiting triggers that arrived before ``before`` (``time.perf_counter()`` s)."""
        ...

    def refuse_triggers(self, handler: Callable[[Trigger], str]) -> None:
        """Answer every trigger from now on REJECT with the reason ``handler`` returns (shutdown)."""
        ...

    def report(self, part_id: str, decision: Verdict, reason: str | None, deadline: float | None = None) -> bool | None:
        """Send PASS/REJECT for ``part_id`` (never blocks, never drops); a PASS that cannot go out before
        ``deadline`` (``time.perf_counter()`` s) goes out as a REJECT."""
        ...

    def outcomes(self) -> list[tuple[str, bool, float, Verdict]]:
        """Decisions settled since the last call: (part id, acknowledged by the PLC, ``time.perf_counter()``, the
        decision as sent: PASS or REJECT)."""
        ...

    def flush(self, timeout_s: float) -> bool:
        """Wait until every decision is settled; True if that happened within ``timeout_s``."""
        ...

    def close(self) -> object:
        """Give up what is still unacknowledged and close the port (idempotent)."""
        ...


class NoLink:
    """Trigger-free operation without a PLC: every frame is a part, decisions go only to the log."""

    triggered = False
    has_plc = False

    def next_trigger(self, timeout_s: float) -> Trigger | None:
        return None

    def expired(self, before: float) -> list[Trigger]:
        return []

    def refuse_triggers(self, handler: Callable[[Trigger], str]) -> None:
        pass

    def report(self, part_id: str, decision: Verdict, reason: str | None, deadline: float | None = None) -> bool | None:
        return None

    def outcomes(self) -> list[tuple[str, bool, float, Verdict]]:
        return []

    def flush(self, timeout_s: float) -> bool:
        return True

    def close(self) -> None:
        pass
