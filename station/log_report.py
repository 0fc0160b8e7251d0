"""Summary of an inspection log: counts, reject rate, latency percentiles, score histogram, and plots."""

from __future__ import annotations

from collections import Counter
from collections.abc import Iterable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from model.draem.frame_checks import FRAME_CHECKS, OWN_RENDERS_NOISE_LEVEL_MAX, SIGNED_CHECKS, UNSEEN_LIMIT
from station.decision import SECOND_NAME, Verdict
from station.drift import (
    LOOK_ADVICE,
    LOOK_WARN_LEVEL,
    TURN_ADVICE,
    TURN_WARN_DEG,
    VIEW_ADVICE,
    VIEW_WARN_SHARE,
    line_look,
    line_turn,
    too_many_outside,
)
from station.inspection_log import DECISIONS

PERCENTILES = (50, 90, 99)
NOISY_LINE_LEVEL = 1.5
"""Median ``noise_level`` from which the report warns: above the model's own renders' highest
(``OWN_RENDERS_NOISE_LEVEL_MAX``)."""

REJECT_CAUSES: tuple[tuple[str, tuple[str, ...]], ...] = (
    ("part turned", ("the part lay turned",)),
    ("part bent (shape check)", ("bottom edge bends",)),
    ("edge steps (outline check)", ("an edge steps",)),
    ("frame unlike the model's line", ("unlike the model's line",)),
    ("score over threshold", ("> threshold",)),
    ("log not writable", ("not recorded:",)),
    ("PLC link", ("the PASS was not",)),
    ("station stopping", ("station stopping",)),
    ("not judged in time", ("not judged in time",)),
    ("camera missed trigger pulse", ("missed its trigger pulse",)),
    ("no part in view", ("no part in view",)),
    ("frame lost", ("lost in transport", "lost before reaching the host")),
    ("no frame", ("no frame", "camera error", "no usable frame")),
    ("model busy or failed", ("model busy", "failed:", "model score is")),
    ("invalid pixels", ("input pixels invalid",)),
    ("queue full", ("processing queue full",)),
)
"""Why a part was rejected or not inspected, read from its reason, first match wins (the reasons are worded in
``station.loop``, ``station.decision``, ``station.inspector`` and ``model.draem.frame_checks``; a test keeps each
cause's words in that code; a score over threshold with a frame check beyond its limit counts as that check's cause,
a part turned beyond ``TURN_LIMIT_DEG`` first: a turned part's edges read bent and stepped;
a part partly outside the model's view counts by what else its reason says: the share of such parts tells the line,
``station.drift.VIEW_WARN_SHARE``).
A reason matching none counts as "other"."""


def reject_cause(reason: str | None) -> str:
    """The ``REJECT_CAUSES`` name of a reject's or a not-inspected row's ``reason``; a reject by the second camera
    alone (``station.decision.join``: its reason starts "second camera: ") is that cause with "second camera: "
    before it."""
    text = reason or ""
    if text.startswith(f"{SECOND_NAME}: "):
        return f"{SECOND_NAME}: {reject_cause(text[len(SECOND_NAME) + 2:])}"
    for cause, needles in REJECT_CAUSES:
        if any(n in text for n in needles):
            return cause
    return "other"


@dataclass(frozen=True)
class LogSummary:
    """Counts per decision, reject rate among judged parts (pass + reject; "empty" frames are not judged), total
    latency percentiles (ms), score histogram, and the confusion against ground truth where the log has it
    (simulated camera): ``<truth>_<decision>`` with truth "good"/"bad" (a part in view, by its label) or "none"
    (``ground_truth_present`` false: no part in view) and decision "pass", "reject" or "empty" ("good_empty"/
    "bad_empty": a part the presence check missed; "none_pass"/"none_reject": an empty view it let through; logs
    of schema version 1 have no presence column, so their empty views are not in it)."""

    counts: dict[str, int]
    reject_rate: float
    latency_ms: dict[str, float]
    score_bins: list[float]
    score_hist: dict[str, list[int]]
    confusion: dict[str, int] = field(default_factory=dict)
    first_unix_s: float | None = None
    last_unix_s: float | None = None
    drift_parts: int = 0
    """Parts judged while a drift warning was in force (``drift`` column, schema version 3)."""
    last_drift: str | None = None
    """The newest drift warning in the log."""
    frame_checks: dict[str, dict[str, float]] = field(default_factory=dict)
    """Per model frame check (``FRAME_CHECKS``, schema version 4; ``edge_bend`` version 6) over the parts that have it:
    median, p99, max; of a signed check (``SIGNED_CHECKS``: ``edge_bend``), of its size."""
    reject_causes: dict[str, int] = field(default_factory=dict)
    """Rejected and not-inspected parts per cause (``reject_cause``), most first: "score over threshold" is the
    model's judgement, every other cause a part the station could not judge."""
    outside_view_parts: int = 0
    """Parts, passed or rejected, some of which lay outside the model's view (``unseen_fraction`` over
    ``UNSEEN_LIMIT``, schema version 8): the camera turned from square or parts off their place."""
    view_parts: int = 0
    """Parts with ``unseen_fraction`` (the model ran and has a variation member)."""
    turn_median_deg: float | None = None
    """The median ``turn_deg`` (schema version 9) of the parts that have it, when it calls for the turn warning
    (``station.drift.line_turn``: at least ``TURN_WARN_MIN_PARTS`` parts, beyond +-``TURN_WARN_DEG``); else None."""
    turn_parts: int = 0
    """Parts with ``turn_deg`` (the model ran and reads a turn)."""
    look_median: float | None = None
    """The median ``look_level`` (schema version 10) of the parts that have it, when it calls for the look warning
    (``station.drift.line_look``: at least ``LOOK_WARN_MIN_PARTS`` parts, above ``LOOK_WARN_LEVEL``); else None."""
    look_parts: int = 0
    """Parts with ``look_level`` (the model ran and blends its look network)."""


def summarize(rows: Iterable[dict[str, Any]], bins: int = 20) -> LogSummary:
    """One pass over log rows (as ``InspectionLog.rows`` yields them)."""
    counts: Counter[str] = Counter()
    latencies: list[float] = []
    scores: dict[str, list[float]] = {Verdict.PASS: [], Verdict.REJECT: []}
    confusion: Counter[str] = Counter()
    times: list[float] = []
    drift_parts, last_drift = 0, None
    checks: dict[str, list[float]] = {k: [] for k in FRAME_CHECKS}
    causes: Counter[str] = Counter()
    outside = viewed = 0
    turns: list[float] = []
    looks: list[float] = []
    for r in rows:
        if r.get("look_level") is not None:
            looks.append(r["look_level"])
        if r.get("turn_deg") is not None:
            turns.append(r["turn_deg"])
        if r.get("unseen_fraction") is not None:
            viewed += 1
            outside += r["unseen_fraction"] > UNSEEN_LIMIT
        for k in FRAME_CHECKS:
            if r.get(k) is not None:
                checks[k].append(abs(r[k]) if k in SIGNED_CHECKS else r[k])
        counts[r["decision"]] += 1
        if r["decision"] in (Verdict.REJECT, Verdict.NOT_INSPECTED):
            causes[reject_cause(r["reason"])] += 1
        if r.get("drift"):
            drift_parts, last_drift = drift_parts + 1, r["drift"]
        times.append(r["time_unix_s"])
        if r["total_ms"] is not None:
            latencies.append(r["total_ms"])
        if r["score"] is not None and r["decision"] in scores:
            scores[r["decision"]].append(r["score"])
        if r["decision"] in (Verdict.PASS, Verdict.REJECT, Verdict.EMPTY):
            if r["ground_truth_present"] is False:
                confusion[f"none_{r['decision']}"] += 1
            elif r["ground_truth_label"] is not None:
                truth = "bad" if r["ground_truth_label"] else "good"
                confusion[f"{truth}_{r['decision']}"] += 1
    judged = counts[Verdict.PASS] + counts[Verdict.REJECT]
    edges = np.linspace(0.0, 1.0, bins + 1)
    return LogSummary(
        counts={d: counts[d] for d in DECISIONS},
        reject_rate=counts[Verdict.REJECT] / judged if judged else 0.0,
        latency_ms={f"p{q}": float(np.percentile(latencies, q)) for q in PERCENTILES} if latencies else {},
        score_bins=edges.tolist(),
        score_hist={d: np.histogram(np.clip(s, 0, 1), edges)[0].tolist() for d, s in scores.items()},
        confusion=dict(confusion),
        first_unix_s=min(times) if times else None,
        last_unix_s=max(times) if times else None,
        drift_parts=drift_parts,
        last_drift=last_drift,
        frame_checks={k: {"median": float(np.median(v)), "p99": float(np.percentile(v, 99)), "max": float(max(v))}
                      for k, v in checks.items() if v},
        reject_causes=dict(causes.most_common()),
        outside_view_parts=outside,
        view_parts=viewed,
        turn_median_deg=line_turn(turns),
        turn_parts=len(turns),
        look_median=line_look(looks),
        look_parts=len(looks),
    )


def format_summary(s: LogSummary) -> str:
    lines = ["| decision | parts |", "|---|---|"] + [f"| {d} | {n} |" for d, n in s.counts.items()]
    lines.append(f"\nreject rate (of judged parts): {100 * s.reject_rate:.2f} %")
    if s.reject_causes:
        lines.append("rejects by cause: " + ", ".join(f"{c} {n}" for c, n in s.reject_causes.items()))
    if s.latency_ms:
        lines.append("latency grab->decision: " + ", ".join(f"{k} {v:.1f} ms" for k, v in s.latency_ms.items()))
    if s.confusion:
        c = s.confusion
        lines.append(f"against ground truth: good parts passed {c.get('good_pass', 0)}, good rejected "
                     f"{c.get('good_reject', 0)}, bad rejected {c.get('bad_reject', 0)}, bad passed (escapes) "
                     f"{c.get('bad_pass', 0)}")
        missed = c.get("good_empty", 0) + c.get("bad_empty", 0)
        if missed or s.counts.get("empty"):
            lines.append(f"logged empty (no part in view): {s.counts.get('empty', 0)}, of which {missed} showed a "
                         "part (presence check missed it)")
        judged_empty = c.get("none_pass", 0) + c.get("none_reject", 0)
        if judged_empty or c.get("none_empty"):
            lines.append(f"frames without a part: {c.get('none_empty', 0)} logged empty, {judged_empty} judged as a "
                         "part (presence check let them through)")
    if s.drift_parts:
        lines.append(f"DRIFT: {s.drift_parts} part(s) judged while a drift warning was in force (frames outside the "
                     f"model's trained range, or parts outside its view); last warning: {s.last_drift}")
    for k, v in s.frame_checks.items():
        name = f"|{k}|" if k in SIGNED_CHECKS else k
        lines.append(f"{name}: median {v['median']:.3f}, p99 {v['p99']:.3f}, max {v['max']:.3f}")
    noise = s.frame_checks.get("noise_level", {}).get("median", 0.0)
    if noise >= NOISY_LINE_LEVEL:
        lines.append(f"NOISE: the frames' median noise level is {noise:.2f} times the model's good parts' (at most "
                     f"{OWN_RENDERS_NOISE_LEVEL_MAX} on its own renders): the camera is noisier than the model's "
                     "line; lower the gain or station adapt on this line's good parts")
    if too_many_outside(s.outside_view_parts, s.view_parts):
        lines.append(f"VIEW: {s.outside_view_parts} of {s.view_parts} parts lay partly outside the model's view as "
                     f"registered (over {100 * VIEW_WARN_SHARE:g} %; judged from the frame's border there): "
                     f"{VIEW_ADVICE}")
    if s.turn_median_deg is not None:
        lines.append(f"TURN: the {s.turn_parts} parts lay turned {s.turn_median_deg:+.1f} degrees from the model's "
                     f"good parts at the median (beyond {TURN_WARN_DEG:g}): {TURN_ADVICE}")
    if s.look_median is not None:
        lines.append(f"LOOK: the {s.look_parts} parts' look level is {s.look_median:.2f} at the median (above "
                     f"{LOOK_WARN_LEVEL:g}): {LOOK_ADVICE}")
    return "\n".join(lines) + "\n"


def plot_summary(s: LogSummary, threshold: float | None, path: str | Path) -> Path:
    """Score histogram per decision (with the threshold), decision counts and rejects by cause, as one PNG."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (ax1, ax2, ax3) = plt.subplots(1, 3, figsize=(14, 3.8), gridspec_kw={"width_ratios": [2, 1, 1.4]})
    centers = (np.array(s.score_bins[:-1]) + np.array(s.score_bins[1:])) / 2
    width = s.score_bins[1] - s.score_bins[0]
    ax1.bar(centers, s.score_hist[Verdict.PASS], width=width, color="tab:green", alpha=0.7, label="pass")
    ax1.bar(centers, s.score_hist[Verdict.REJECT], width=width, color="tab:red", alpha=0.7, label="reject",
            bottom=s.score_hist[Verdict.PASS])
    if threshold is not None:
        ax1.axvline(threshold, color="k", ls="--", label=f"threshold {threshold:.3g}")
    ax1.set(xlabel="anomaly score", ylabel="parts", title="score histogram", xlim=(0, 1))
    ax1.legend()
    ax2.bar(list(s.counts), list(s.counts.values()), color=["tab:green", "tab:red", "tab:gray", "tab:orange"])
    ax2.set(title="decisions", ylabel="parts")
    ax2.tick_params(axis="x", rotation=30)
    causes = list(s.reject_causes)[::-1]
    bars = ax3.barh(causes, [s.reject_causes[c] for c in causes],
                    color=["tab:red" if c == "score over threshold" else "tab:orange" for c in causes])
    ax3.bar_label(bars, padding=2)
    ax3.set(title="rejects by cause", xlabel="parts")
    fig.tight_layout()
    out = Path(path)
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out, dpi=100)
    plt.close(fig)
    return out
