"""Several ``station eval`` reports side by side, per defect type (``station compare``).

The standard held-out report: per defect type, the industrial pair (defective parts caught at 1 % and 5 % of good
parts rejected, thresholds from validation) and image AUROC of the model that trained on rendered defects of that
type ("trained on"), of the one that never saw it ("held out", ``station train --holdout-type``) and of the one that
saw no rendered defect at all ("synthetic only", DRAEM's recipe), and on a kind its training never drew ("never in
training", e.g. ``sim.defects.NEW_KINDS``). Each report's rows say which of those it is
(``station eval``'s ``in_training`` column), so the reports can be given in any order.
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

from station.errors import UserError

if TYPE_CHECKING:
    import numpy as np

STATUSES = ("synthetic only", "never in training", "held out", "trained on")
"""``in_training`` values, in the order the comparison shows them."""
CAUGHT = ("caught_at_1%_false_rejects", "caught_at_5%_false_rejects")


def read_report(folder: str | Path) -> dict[str, Any]:
    """``eval.json`` of a ``station eval --out`` folder; UserError naming it when missing or without industrial
    rows."""
    path = Path(folder) / "eval.json"
    try:
        report = json.loads(path.read_text())
    except (OSError, ValueError) as exc:  # ValueError: not JSON, or not UTF-8
        raise UserError(f"{path}: not a station eval report ({exc})") from None
    if not isinstance(report, dict):
        raise UserError(f"{path}: not a station eval report (a JSON {type(report).__name__})")
    if not report.get("industrial"):
        raise UserError(f"{path}: no industrial rows ({report.get('industrial_note') or 'none'}); "
                        f"evaluate on a split other than val, with --val-data for a held-out set")
    return report


def by_type(reports: dict[str, dict[str, Any]]) -> list[dict[str, Any]]:
    """One row per defect type and status: the figures of the report where the type has that status (the first
    given wins when several have it). ``reports``: name -> eval.json."""
    found: dict[tuple[str, str], dict[str, Any]] = {}
    for name, rep in reports.items():
        for row in rep["industrial"]:
            if row["type"] == "all":
                continue
            found.setdefault((row["type"], row["in_training"]), {"model": name, **row})
    rows = []
    for t in sorted({t for t, _ in found}):
        for status in STATUSES:
            row = found.get((t, status))
            if row:
                rows.append({"type": t, "in_training": status, "model": row["model"], "parts": row["parts"],
                             "image_auroc": row["image_auroc"], **{k: row[k] for k in CAUGHT}})
    return rows


def plot(rows: list[dict[str, Any]], path: Path) -> None:
    """Grouped bars: per type, parts caught at 5 % false rejects per status."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    types = sorted({r["type"] for r in rows})
    fig, ax = plt.subplots(figsize=(1.2 + 1.3 * len(types), 3.2))
    x = np.arange(len(types))
    width = 0.8 / len(STATUSES)
    for k, status in enumerate(STATUSES):
        vals = [next((r[CAUGHT[1]] for r in rows if r["type"] == t and r["in_training"] == status), np.nan)
                for t in types]
        ax.bar(x + (k - (len(STATUSES) - 1) / 2) * width, vals, width, label=status)
    ax.set_xticks(x, types)
    ax.set(ylim=(0, 1), ylabel="caught at 5 % of good rejected", title="per defect type, held-out set")
    ax.legend(fontsize=7)
    fig.savefig(path, dpi=120, bbox_inches="tight")
    plt.close(fig)


def compare(folders: list[str], out: str | Path, plots: bool = True) -> tuple[list[dict[str, Any]], str]:
    """Read the reports, write ``compare.json``, ``compare.md`` (and ``compare.png``) into ``out``; returns the
    rows and the Markdown table."""
    from station.benchmarks.report import markdown_table

    reports = {str(f): read_report(f) for f in folders}
    rows = by_type(reports)
    if not rows:
        raise UserError(f"{', '.join(folders)}: no per-type rows to compare")
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    sets = sorted({str(r.get("data")) for r in reports.values()})
    table = (f"Per defect type on {', '.join(sets)}: parts caught at a fixed share of good parts rejected "
             f"(thresholds from validation, held fixed) and image AUROC, by whether the model trained on rendered "
             f"defects of that type:\n\n" + markdown_table(rows, list(rows[0])))
    (out / "compare.json").write_text(json.dumps({"reports": list(reports), "data": sets, "rows": rows}, indent=1))
    (out / "compare.md").write_text(table + "\n")
    if plots:
        plot(rows, out / "compare.png")
    return rows, table


def read_scores(folder: str | Path) -> dict[int, tuple[int, str, float]]:
    """``scores.csv`` of a ``station eval --out`` folder: dataset index -> (label, defect type, decision score);
    UserError naming the file when it is missing or unreadable (reports from before 2026-11-27 lack it)."""
    import csv

    path = Path(folder) / "scores.csv"
    try:
        with open(path, newline="") as fh:
            return {int(r["index"]): (int(r["label"]), r["defect_type"], float(r["score"]))
                    for r in csv.DictReader(fh)}
    except (OSError, KeyError, ValueError) as exc:
        raise UserError(f"{path}: no per-part scores ({exc}); run station eval again to write them") from None


def read_faces(folder: str | Path) -> dict[int, str]:
    """The face each defect lies on (``scores.csv``'s ``face`` column, ``station eval`` on a rendered set since
    2026-12-01): dataset index -> face, for the parts whose face is known; empty for older reports."""
    import csv

    with open(Path(folder) / "scores.csv", newline="") as fh:
        return {int(r["index"]): r["face"] for r in csv.DictReader(fh) if r.get("face")}


def paired(folders: list[str], out: str | Path, resamples: int = 1000) -> tuple[list[dict[str, Any]], str]:
    """Each report after the first against the first, on the same parts (``model.draem.metrics.paired_auroc_gains``):
    image AUROC overall and per type, the gain and its paired bootstrap standard error. Writes ``paired.json`` and
    ``paired.md`` into ``out``; UserError when the reports are not on the same parts."""
    import numpy as np

    from model.draem.metrics import paired_auroc_gains
    from station.benchmarks.report import markdown_table

    if len(folders) < 2:
        raise UserError("--paired compares reports with the first: give two or more")
    scores = {str(f): read_scores(f) for f in folders}
    base_name, base = next(iter(scores.items()))
    idx = sorted(base)
    rows: list[dict[str, Any]] = []
    for name, s in list(scores.items())[1:]:
        if sorted(s) != idx or any(s[i][:2] != base[i][:2] for i in idx):
            raise UserError(f"{name} and {base_name}: not the same parts (indices, labels or types differ); a paired "
                            f"comparison needs both models evaluated on one split of one set")
        gains = paired_auroc_gains(np.array([base[i][0] for i in idx]), [base[i][1] for i in idx],
                                   np.array([base[i][2] for i in idx]), np.array([s[i][2] for i in idx]), resamples)
        rows += [{"model": name, **g} for g in gains]
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    table = (f"Image AUROC on the same parts against {base_name} (base), overall and per defect type (its defective "
             f"parts against all good parts); gain = model - base, se = paired bootstrap over parts "
             f"({resamples} resamples):\n\n" + markdown_table(rows, list(rows[0])))
    (out / "paired.json").write_text(json.dumps({"base": base_name, "reports": list(scores), "rows": rows}, indent=1))
    (out / "paired.md").write_text(table + "\n")
    return rows, table


@dataclass(frozen=True)
class PairDecisions:
    """Per part of two ``station eval`` reports on twin sets, in dataset index order (``pair_decisions``)."""

    index: list[int]
    defective: np.ndarray
    """(N,) bool: either report labels the part defective (a label says what that camera sees)."""
    types: np.ndarray
    """(N,) str: its defect type, from whichever report has one ("" for a good part)."""
    faces: np.ndarray
    """(N,) str: the face the defect lies on, from whichever report knows it ("" unknown)."""
    rules: dict[str, np.ndarray]
    """Rule name -> (N,) bool rejected: the first camera alone, the second alone, both at the split (in that order)."""
    unjudged: tuple[np.ndarray, np.ndarray]
    """(N,) bool per camera: frames its report did not judge (``eval.json``'s ``unjudged``)."""


def pair_decisions(first: str | Path, second: str | Path, split: str | Path) -> PairDecisions:
    """The two-camera rules' decisions per part (``two_cameras``): each camera alone at its report's threshold, then
    both at the ``station split`` report's thresholds; a frame a camera would not judge rejects the part under every
    rule that reads that camera. UserError when the reports are not on the same parts or ``split`` is not a split
    report."""
    import numpy as np

    from model.draem.camera_split import SplitThresholds, split_rejects

    a, b = read_scores(first), read_scores(second)
    idx = sorted(set(a) & set(b))
    if not idx or len(idx) != len(a) or len(idx) != len(b):
        raise UserError(f"{first} and {second} are not reports on the same parts ({len(a)} and {len(b)} parts, "
                        f"{len(idx)} in both)")
    y = np.array([bool(a[i][0] or b[i][0]) for i in idx])
    types = np.array([a[i][1] or b[i][1] for i in idx])
    fa, fb = read_faces(first), read_faces(second)
    faces = np.array([fa.get(i) or fb.get(i) or "" for i in idx])
    sa, sb = (np.array([s[i][2] for i in idx]) for s in (a, b))
    reports = [read_report(first), read_report(second)]
    left = [np.array([str(i) in r.get("unjudged", {}) for i in idx]) for r in reports]
    try:
        chosen = json.loads(Path(split).read_text())
        pair = SplitThresholds(**chosen["splits"][chosen["chosen"]])
    except (OSError, ValueError, KeyError, IndexError, TypeError) as exc:
        raise UserError(f"{split}: not a station split report ({exc})") from None
    alone = [float(r["threshold"]) for r in reports]
    rules = {f"first camera alone (its threshold {alone[0]:.4f})": (sa > alone[0]) | left[0],
             f"second camera alone (its threshold {alone[1]:.4f})": (sb > alone[1]) | left[1],
             f"both, split ({pair.first:.4f}, {pair.second:.4f})": split_rejects(sa, sb, pair) | left[0] | left[1]}
    return PairDecisions(idx, y, types, faces, rules, (left[0], left[1]))


def two_cameras(first: str | Path, second: str | Path, split: str | Path, out: str | Path) -> tuple[dict, str]:
    """A two-camera station (``[second_camera]``) on held-out parts: ``first`` and ``second`` are ``station eval``
    reports of the two cameras' models on twin held-out sets (the same parts), ``split`` the ``station split`` report
    whose chosen thresholds were set on validation. Rules: each camera alone at its report's threshold (its model's
    own), and both at the split's thresholds, as the station decides. Per rule: good parts rejected and defective
    parts caught, overall and per type, and the gain in parts caught over the first camera alone with its paired
    standard error. A frame a camera would not judge (``eval.json``'s ``unjudged``) is rejected by every rule that
    reads that camera, as a triggered station rejects it. A part is defective when either report labels it so (a
    label says what that camera sees), its type from whichever does. Writes ``two-cameras.json`` and ``.md``."""
    import numpy as np

    from sim.defects import FACES

    decided = pair_decisions(first, second, split)
    idx, y, types, faces, rules = decided.index, decided.defective, decided.types, decided.faces, decided.rules
    left = decided.unjudged
    base = next(iter(rules.values()))
    on = [f for f in FACES if (y & (faces == f)).any()]  # faces known (station eval on rendered sets since 2026-12-01)
    rows = []
    for name, rejected in rules.items():
        d = rejected[y].astype(float) - base[y].astype(float)
        rows.append({"rule": name, "good_rejected": int(rejected[~y].sum()), "good": int((~y).sum()),
                     "caught": int(rejected[y].sum()), "defective": int(y.sum()),
                     "gain_points": 100 * float(d.mean()) if y.any() else float("nan"),
                     "gain_se": 100 * float(d.std(ddof=1) / np.sqrt(d.size)) if y.sum() > 1 else float("nan"),
                     "by_type": {str(t): float(rejected[y & (types == t)].mean()) for t in sorted(set(types[y]))},
                     "by_face": {f: float(rejected[y & (faces == f)].mean()) for f in on}})
    kinds = sorted(set(types[y]))
    lines = [f"{len(idx)} parts ({int((~y).sum())} good, {int(y.sum())} defective); frames not judged: first camera "
             f"{int(left[0].sum())}, second camera {int(left[1].sum())}. Reports: {first}, {second}; split: {split}.",
             "", "| rule | good parts rejected | defective parts caught | minus the first camera alone (paired SE) | "
             + " | ".join(kinds) + " |", "|---|---|---|---|" + "---|" * len(kinds)]
    for r in rows:
        good, bad = max(r["good"], 1), max(r["defective"], 1)
        lines.append(f"| {r['rule']} | {r['good_rejected']} of {r['good']} ({r['good_rejected'] / good:.1%})"
                     f" | {r['caught']} of {r['defective']} ({r['caught'] / bad:.1%}) | "
                     f"{r['gain_points']:+.1f} ({r['gain_se']:.1f}) | "
                     + " | ".join(f"{r['by_type'][k]:.0%}" for k in kinds) + " |")
    if on:
        lines += ["", "Defective parts caught by the face the defect lies on (station/defect_face.py; "
                  f"{int((y & (faces == '')).sum())} of unknown face left out):", "",
                  "| rule | " + " | ".join(f"{f} ({int((y & (faces == f)).sum())})" for f in on) + " |",
                  "|---|" + "---|" * len(on)]
        lines += [f"| {r['rule']} | " + " | ".join(f"{r['by_face'][f]:.0%}" for f in on) + " |" for r in rows]
    text = "\n".join(lines)
    report = {"first": str(first), "second": str(second), "split": str(split), "parts": len(idx), "rules": rows}
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    (out / "two-cameras.json").write_text(json.dumps(report, indent=1))
    (out / "two-cameras.md").write_text(text + "\n")
    return report, text
