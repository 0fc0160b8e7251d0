"""``station eval``'s industrial figures count a frame the station would not judge as rejected, as the station
does when the PLC announced the part (fail closed), instead of as the model scored it."""

from __future__ import annotations

import json
from pathlib import Path

from line_sets import make_line_set
from test_run import make_model  # same folder (pytest puts it on sys.path)

from station.cli import main


def test_frames_the_station_would_not_judge_count_as_rejected_in_the_industrial_figures(tmp_path: Path) -> None:
    # test split: 0, 1, 10, 11, ..., 70, 71 (8 good, 8 defective: i % 10 == 1); val split: 2, 12, 22, ...
    data = make_line_set(tmp_path / "ds", 80, defective=lambda i: i % 10 == 1, blank=lambda i: i in (10, 20),
                         polar_only=lambda i: i == 30)
    model = make_model(tmp_path / "m" / "last", ("intensity", "aolp"))
    reports = {}
    for rule in ("dolp_contrast", "row_contrast"):
        out = tmp_path / rule
        assert main(["eval", "--model", str(model), "--data", str(data), "--no-plots", "--no-synthetic",
                     "--presence-rule", rule, "--out", str(out)]) == 0
        reports[rule] = json.loads((out / "eval.json").read_text())
    dolp, rows = reports["dolp_contrast"], reports["row_contrast"]
    # two black frames for either rule; the frame of one intensity (a DoLP patch only) for the row rule too
    assert dolp["unjudged"] == {"10": "no part in view", "20": "no part in view"}
    assert rows["unjudged"] == {"10": "no part in view", "20": "no part in view", "30": "no part in view"}
    assert "2 evaluated frames the station would not judge (2 good, 0 defective; presence rule dolp_contrast) " \
           "count as rejected" in dolp["industrial_note"]
    assert "3 evaluated frames" in rows["industrial_note"] and "(3 good, 0 defective" in rows["industrial_note"]
    # a good part rejected unseen is a false reject at every rate: at least 2 and 3 of the 8 good test parts
    for report, n_forced in ((dolp, 2), (rows, 3)):
        observed = [float(x.split("observed here ")[1].split(" %")[0])
                    for x in report["industrial_note"].split(", ") if "observed here" in x]
        assert len(observed) == 2 and min(observed) >= 100 * n_forced / 8 - 0.05, report["industrial_note"]
        counts = [int(x.split("observed here ")[1].split("(")[1].split(" of 8:")[0])
                  for x in report["industrial_note"].split(", ") if "observed here" in x]
        assert [round(100 * c / 8, 1) for c in counts] == observed  # with the count behind each share
        assert "of 8: 95 % interval " in report["industrial_note"]
        assert report["rows"][0]["flagged_good"] >= n_forced / 8  # and at the model's own threshold
