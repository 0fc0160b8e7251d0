"""`station eval`'s in_training column: whether the model learned from rendered defects of each type it reports."""

from __future__ import annotations

from types import SimpleNamespace

from station.commands.eval import FALSE_REJECTS, industrial_rows


def _report(types: list[str]) -> SimpleNamespace:
    def det(t: str) -> SimpleNamespace:
        return SimpleNamespace(defect_type=t, n_defective=3, image_auroc=0.9, caught={fr: 0.5 for fr in FALSE_REJECTS})
    return SimpleNamespace(overall=det("all"), per_type={t: det(t) for t in types})


def _status(types: list[str], meta: dict) -> dict[str, str]:
    return {r["type"]: r["in_training"] for r in industrial_rows(_report(types), meta)}


def test_a_kind_the_training_never_drew_is_not_called_trained_on() -> None:
    # a record from before the learned kinds were recorded: its sets could draw the five default kinds only
    older = {"residual": {"holdout_type": "dent"}}
    assert _status(["dent", "stain", "blister", "debris"], older) == {
        "all": "", "dent": "held out", "stain": "trained on", "blister": "never in training",
        "debris": "never in training"}
    # a record that names the kinds its networks learned from
    named = {"rendered_defects": {"holdout_type": None, "types": ["stain"]}}
    assert _status(["dent", "stain"], named) == {"all": "", "dent": "never in training", "stain": "trained on"}
    # networks whose record names no type learned from none of them
    empty = {"residual": {"holdout_type": None, "types": []}}
    assert _status(["dent"], empty) == {"all": "", "dent": "never in training"}
    # no network learned from a rendered defect
    assert _status(["dent", "blister"], {}) == {"all": "", "dent": "synthetic only", "blister": "synthetic only"}


def test_station_compare_keeps_a_kind_never_in_training() -> None:
    from station.eval_compare import by_type

    def row(t: str, status: str) -> dict:
        return {"type": t, "in_training": status, "parts": 3, "image_auroc": 0.9, "caught_at_1%_false_rejects": 0.5,
                "caught_at_5%_false_rejects": 0.6}
    rows = by_type({"shipped": {"industrial": [row("all", ""), row("blister", "never in training"),
                                               row("dent", "trained on")]}})
    assert [(r["type"], r["in_training"]) for r in rows] == [("blister", "never in training"), ("dent", "trained on")]
