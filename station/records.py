"""The inspection loop's log rows (``RecordKeeper``): each written before the PLC hears of its part (write-ahead),
kept in memory and retried while the log cannot be written (its part rejected), and settled with the PLC's
acknowledgements. Rules: docs/fail-closed.md."""

from __future__ import annotations

import dataclasses
import json
import logging
import threading
from collections import deque

from station.decision import Decision, Verdict
from station.inspection_log import InspectionLog, InspectionRecord, LogError

log = logging.getLogger(__name__)


class RecordKeeper:
    """Writes the log rows of the loop (from the processing thread, and from the PLC link's thread at shutdown):
    write-ahead of the PLC, and fail closed when the log cannot be written.

    A row that cannot be written (disk full, I/O error) is kept in memory (up to ``MAX_BACKLOG`` rows) and retried
    before every later row, and its part is rejected at the PLC with the reason; the error is logged every time.
    ``settle`` records the PLC's acknowledgements (``io_delivered``) of rows written or still waiting."""

    MAX_BACKLOG = 100_000

    def __init__(self, inspection_log: InspectionLog) -> None:
        self.log = inspection_log
        self._lock = threading.RLock()
        self._backlog: deque[tuple[InspectionRecord, float, bool]] = deque()  # (record, decided at, awaits PLC)
        self._row_of: dict[str, tuple[int, float, Verdict]] = {}  # part id -> (row id, decided at, decision)
        self._unsettled: dict[str, tuple[bool, float, Verdict]] = {}  # (acknowledged, when, sent) not yet in the log
        self.lost_rows = 0

    @property
    def backlog(self) -> int:
        return len(self._backlog)

    def write(self, record: InspectionRecord, awaits_plc: bool, t_decided: float) -> InspectionRecord:
        """Write ``record`` (after any backlog) and return what was recorded: the record itself, or, when the log
        fails, the same part rejected with the log's error as its reason (kept in the backlog). ``t_decided``
        (``time.perf_counter()``): when the decision was made, for ``io_ms`` once the PLC acknowledges it."""
        with self._lock:
            try:
                self._flush_backlog()
                row_id = self.log.append(record)[0]
            except LogError as exc:
                log.error("%s; part %s is rejected (fail closed)", exc, record.part_id)
                if record.decision == Verdict.PASS:
                    record = dataclasses.replace(record, decision=Verdict.REJECT,
                                                 reason=f"not recorded: {exc}; judged {record.decision}")
                self._keep((record, t_decided, awaits_plc))
                return record
            if awaits_plc and record.part_id is not None:
                self._row_of[record.part_id] = (row_id, t_decided, record.decision)
            return record

    def amend(self, record: InspectionRecord, decision: Decision) -> InspectionRecord:
        """``record`` (written or kept) with another decision and its reason, in the log too; when the row cannot
        be amended the error is logged (the old row stays) and the part is still answered with the new decision."""
        new = dataclasses.replace(record, decision=decision.decision, reason=decision.reason)
        reason = decision.reason or ""
        with self._lock:
            row = self._row_of.get(record.part_id or "")
            if row is None:  # kept in the backlog, not written yet
                for i, (r, t, awaits) in enumerate(self._backlog):
                    if r is record:
                        self._backlog[i] = (new, t, awaits)
                return new
            try:
                self.log.amend_decision(row[0], new.decision, reason)
                self._row_of[record.part_id or ""] = (row[0], row[1], new.decision)
            except LogError as exc:
                log.error("%s; row %d still says %s, part %s is rejected", exc, row[0], record.decision,
                          record.part_id)
        return new

    def settle(self, outcomes: list[tuple[str, bool, float, Verdict]]) -> None:
        """Record the PLC's answers: ``io_delivered`` True and ``io_ms`` from decision to acknowledgement for an
        acknowledged decision (an unacknowledged one keeps False); a pass the link had to send as a reject (too
        late) becomes a reject in its row."""
        with self._lock:
            self._unsettled.update((p, (ok, t, sent)) for p, ok, t, sent in outcomes)
            try:
                self._flush_backlog()
                written = [p for p in self._unsettled if p in self._row_of]
                for p in written:
                    row_id, _, decided = self._row_of[p]
                    if decided == Verdict.PASS and self._unsettled[p][2] != Verdict.PASS:
                        self.log.amend_decision(row_id, Verdict.REJECT, "not answered in time: the PASS was not "
                                                                  "delivered before the part's deadline (PLC link "
                                                                  "down, behind or not acknowledging) and went out "
                                                                  "as a REJECT")
                        self._row_of[p] = (row_id, self._row_of[p][1], Verdict.REJECT)
                self.log.set_delivered({self._row_of[p][0]: (True, 1e3 * (self._unsettled[p][1] - self._row_of[p][1]))
                                        for p in written if self._unsettled[p][0]})
            except LogError as exc:
                log.error("%s (PLC acknowledgements kept for later)", exc)
                return
            for p in written:
                del self._row_of[p], self._unsettled[p]
            while len(self._unsettled) > self.MAX_BACKLOG:  # answers for rows neither written nor kept
                del self._unsettled[next(iter(self._unsettled))]

    def give_up(self) -> None:
        """At shutdown: rows still unwritten go to the process log (stderr), one JSON line each, so that no record
        vanishes without a trace; their parts were rejected at the PLC. A row that says pass for a part answered
        REJECT, which could not be corrected, is named there too (``UNRECORDED AMENDMENT``)."""
        with self._lock:
            try:
                self._flush_backlog()
            except LogError as exc:
                log.error("%s: %d row(s) could not be written; they follow as JSON (parts rejected at the PLC)",
                          exc, len(self._backlog))
            for r, _, _ in self._backlog:
                log.error("UNRECORDED ROW %s", json.dumps(dataclasses.asdict(r)))
            self.lost_rows += len(self._backlog)
            self._backlog.clear()
            self.settle([])  # a last try at the PLC's answers still waiting for the log (it logs its own error)
            for p, (_, _, sent) in self._unsettled.items():
                row = self._row_of.get(p)
                if row is not None and row[2] == Verdict.PASS and sent != Verdict.PASS:
                    log.error("UNRECORDED AMENDMENT row %d part %s says pass but was answered %s at the PLC: the row "
                              "could not be corrected", row[0], p, sent)
                    self.lost_rows += 1

    def _keep(self, entry: tuple[InspectionRecord, float, bool]) -> None:
        if len(self._backlog) >= self.MAX_BACKLOG:
            dropped, _, _ = self._backlog.popleft()
            log.error("UNRECORDED ROW %s", json.dumps(dataclasses.asdict(dropped)))
            self.lost_rows += 1
        self._backlog.append(entry)

    def _flush_backlog(self) -> None:
        """Write the rows kept while the log failed, oldest first; those awaiting the PLC's answer get it from
        ``settle`` like any other row (it may have come meanwhile, or come later)."""
        while self._backlog:
            r, t_decided, awaits_plc = self._backlog[0]
            row_id = self.log.append(r)[0]  # raises LogError: the rest stays kept
            self._backlog.popleft()
            if awaits_plc and r.part_id is not None:
                self._row_of[r.part_id] = (row_id, t_decided, r.decision)
