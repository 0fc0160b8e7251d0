"""`make model` (scripts/make-model.sh) is the shipped recipe: dry-run with a `station` that only records its
arguments, it asks for the decision each model needs, whatever the commands' defaults are."""

from __future__ import annotations

import itertools
import os
import subprocess
import tomllib
from pathlib import Path

from sim.defects import DEFECT_TYPES, NEW_KINDS

ROOT = Path(__file__).resolve().parents[1]


def stub_run(tmp_path: Path, station: str, empty: tuple[str, ...] = (), **env_vars: str) -> tuple[int, list[str]]:
    """make-model.sh run with `station` the bash script ``station`` (it appends what it records to "$CALLS"), SHIP=0
    and ``env_vars`` set (an empty value unsets the variable; the names in ``empty`` are set, to ""): its return code
    and the lines recorded, in order."""
    calls = tmp_path / "calls"
    stub = tmp_path / "bin"
    stub.mkdir()
    (stub / "station").write_text("#!/bin/bash\n" + station)
    (stub / "station").chmod(0o755)
    env = {**os.environ, "BIN": str(stub), "RUNS": str(tmp_path / "runs"), "SHIP": "0", "CALLS": str(calls),
           **env_vars}
    env = {k: v for k, v in env.items() if v} | dict.fromkeys(empty, "")
    done = subprocess.run(["bash", str(ROOT / "scripts" / "make-model.sh")], env=env, capture_output=True)
    return done.returncode, calls.read_text().splitlines() if calls.exists() else []


def dry_run(tmp_path: Path, empty: tuple[str, ...] = (), **env_vars: str) -> list[list[str]]:
    """make-model.sh run with a `station` that only records its arguments (and ``env_vars`` and ``empty`` set as
    stub_run sets them): each call's arguments, in order."""
    rc, lines = stub_run(tmp_path, 'echo "$*" >> "$CALLS"\n', empty, **env_vars)
    assert rc == 0
    return [line.split() for line in lines]


def out_name(args: list[str], tmp_path: Path) -> str:
    """The ``--out`` (or else ``--model``) of one recorded call, relative to the dry run's RUNS."""
    flag = "--out" if "--out" in args else "--model"
    return args[args.index(flag) + 1].removeprefix(str(tmp_path / "runs") + "/")


def test_make_model_states_each_models_decision(tmp_path: Path) -> None:
    """The recipe with one training of the look (LOOK_DRAWS=1; the shipped three draws and their choice:
    test_look_draws_train_the_look_k_times_and_keep_the_one_a_lens_moves_least)."""
    calls = dry_run(tmp_path, LOOK_DRAWS="1")
    variation = [args for args in calls if args[0] == "variation"]
    assert [(out_name(a, tmp_path), a[a.index("--decision") + 1]) for a in variation] == [("band-variation",
                                                                                           "variation")]
    # the shipped decision (model/weights/README.md): its look network, and one per held-out type, all second looks
    # of the same variation model, each thresholded on the line as built
    residual = {out_name(a, tmp_path): a for a in calls if a[0] == "residual"}
    types = ["dent", "scratch", "stain", "chip", "missing_stud"]
    assert sorted(residual) == sorted(["band-look", *(f"holdout-{t}" for t in types)])  # two at a time: any order
    for name, args in residual.items():
        assert "--second-look" in args and args[args.index("--model") + 1] == str(tmp_path / "runs/band-variation")
        assert args[args.index("--holdout-type") + 1] == name.removeprefix("holdout-") if "holdout" in name else (
            "--holdout-type" not in args)
    thresholded = [(out_name(a, tmp_path), a[a.index("--data") + 1]) for a in calls if a[0] == "threshold"]
    looks = ["band-look", *(f"holdout-{t}" for t in types)]
    assert sorted(n for n, _ in thresholded) == sorted(looks)  # finished two at a time: any order
    assert {d for n, d in thresholded} == {"data/line-pv-val"}
    evals = [out_name(a, tmp_path) for a in calls if a[0] == "eval"]
    assert sorted(f"eval-holdout-{t}" for t in types) == sorted(e for e in evals if "holdout" in e)
    # rule 70: the shape check added in place to the shipped model and to each look without a type, from the fit's
    # train and calibration sets, before that look is thresholded, and every look before any evaluation
    shaped = [(out_name(a, tmp_path), a[a.index("--model") + 1], a[a.index("--data") + 1],
               a[a.index("--val-data") + 1]) for a in calls if a[0] == "shape"]
    assert sorted(n for n, *_ in shaped) == sorted(looks)
    assert all(m == str(tmp_path / "runs" / n) and d == "data/line-ef-train" and v == "data/line-ef-val"
               for n, m, d, v in shaped)
    for name in looks:
        steps = [a[0] for a in calls if a[0] in ("residual", "shape", "blend", "threshold") and out_name(a, tmp_path)
                 == name]
        assert steps == ["residual", "shape", "blend", "threshold"]
    first_eval = min(i for i, a in enumerate(calls) if a[0] == "eval")
    assert all(i < first_eval for i, a in enumerate(calls) if a[0] in ("residual", "shape", "blend", "threshold"))


def test_make_model_blends_each_look_in_place_on_the_threshold_set_after_its_checks(tmp_path: Path) -> None:
    """The shipped decision since stop 123 (docs/results/2026-12-07-blend-rates.md): the look network asked about
    every part, blended with the window, its two thresholds from the set the threshold is set on; BLEND=0 keeps the
    cascade. One draw of the look (LOOK_DRAWS=1): each draw of three is finished alike."""
    calls = dry_run(tmp_path, LOOK_DRAWS="1")
    types = ["dent", "scratch", "stain", "chip", "missing_stud"]
    blended = [(out_name(a, tmp_path), a[a.index("--model") + 1], a[a.index("--data") + 1], a[a.index("--weight") + 1])
               for a in calls if a[0] == "blend"]
    assert sorted(n for n, *_ in blended) == sorted(["band-look", *(f"holdout-{t}" for t in types)])
    assert all(m == str(tmp_path / "runs" / n) and d == "data/line-pv-val" and w == "0.25" for n, m, d, w in blended)
    # each after its checks, whose finding it keeps whole, and before its threshold (the order per look is
    # test_make_model_states_each_models_decision's)
    (tmp_path / "cascade").mkdir()
    assert not [a for a in dry_run(tmp_path / "cascade", BLEND="0") if a[0] == "blend"]


def test_make_model_with_networks_deciding_holds_types_out_of_the_networks(tmp_path: Path) -> None:
    """DECISION=combined: the networks decide, so each held-out type is left out of their training and their
    variation model counts them."""
    calls = dry_run(tmp_path, DECISION="combined")
    decisions = {out_name(a, tmp_path): a[a.index("--decision") + 1] for a in calls if a[0] == "variation"}
    assert decisions.pop("band-variation") == "combined" and len(decisions) == 5
    assert set(decisions.values()) == {"combined"} and not [a for a in calls if a[0] == "residual"]
    held = [a for a in calls if a[0] == "train" and "--holdout-type" in a]
    assert [a[a.index("--holdout-type") + 1] for a in held] == ["dent", "scratch", "stain", "chip", "missing_stud"]


def test_station_train_defaults_are_the_networks_make_model_trains() -> None:
    """Issue 19, point 7: `station train` with no model options trains the shipped networks' kind (make-model.sh's
    MODEL options), not the paper's per-prior ensemble on ground-truth normals that no station can run."""
    import re

    from station.cli import build_parser

    script = (ROOT / "scripts" / "make-model.sh").read_text()
    line = re.search(r"^MODEL=\((.*)\)$", script, re.M)
    priors = re.search(r"^PRIORS=\$\{PRIORS:-(.*)\}$", script, re.M)
    assert line is not None and priors is not None
    recipe = dict(zip(line.group(1).split()[::2], line.group(1).split()[1::2], strict=True))
    assert recipe["--priors"] == '"$PRIORS"'
    recipe["--priors"] = priors.group(1)
    args = build_parser().parse_args(["train", "--data", "d"])
    assert args.priors == recipe["--priors"] and args.fusion == recipe["--fusion"] and args.preset == recipe["--preset"]
    assert args.batch_size == int(recipe["--batch-size"]) and args.seed == int(recipe["--seed"])


def test_the_shipped_variation_fit_is_station_variations_default() -> None:
    """The shipped model's variation model was fitted as `station variation` (and so `make model`) fits by default:
    its blurred copies, clusters and contrast alignment (a checkpoint without a record was fitted before the option,
    without it), read from the sidecar and from the file itself. The sidecar records the clusters the fit kept: up to
    the default, fewer when k-means leaves one under MIN_CLUSTER_PARTS (rule 67's fit: 7 of 8)."""
    import json

    from model.draem.checkpoint import load_checkpoint
    from model.draem.variation import APPEARANCE_CLUSTERS, BLUR_COPIES_SIGMA, GLOBAL_CONTRAST
    from station.cli import build_parser

    meta = json.loads((ROOT / "model" / "weights" / "default.json").read_text())
    fit = meta["train"]["variation"]
    assert fit.get("blur_copies_sigma", 0.0) == BLUR_COPIES_SIGMA
    assert APPEARANCE_CLUSTERS - 1 <= fit.get("clusters", 0) <= APPEARANCE_CLUSTERS
    assert fit.get("global_contrast", "off") == GLOBAL_CONTRAST
    vm = load_checkpoint(ROOT / "model" / "weights" / "default").detector.variation
    assert vm.clusters == fit["clusters"] and vm.contrast_alignment is GLOBAL_CONTRAST
    args = build_parser().parse_args(["variation", "--model", "m", "--data", "d", "--out", "o"])
    assert args.blur_copies is None and args.clusters is None and args.global_contrast is None  # the constants


def test_the_demo_shows_the_line_make_model_renders() -> None:
    """One shipped line: the demo's scene layers (station.assembly.DEMO_SCENE) are the preset files make-model.sh
    renders its sets with, in the same order: two lists that must agree."""
    import re

    from station.assembly import DEMO_SCENE

    line = re.search(r"^PRESET=\((.*)\)$", (ROOT / "scripts" / "make-model.sh").read_text(), re.M)
    assert line is not None
    files = line.group(1).split()[1::2]
    assert [ROOT / f for f in files] == list(DEMO_SCENE)
    assert files[-1] == "sim/presets/panel.toml" and all((ROOT / f).is_file() for f in files)


def test_the_shipped_drift_range_is_the_line_its_variation_model_was_fitted_on() -> None:
    """The drift monitor compares frames with the sidecar's frame statistics: for the shipped model those are the
    good parts its deciding variation model was fitted on (the panel line), not its networks' training set (the
    dome line, which never clips: with that range, `make demo` warned of clipping on its own line's parts)."""
    import json

    meta = json.loads((ROOT / "model" / "weights" / "default.json").read_text())
    stats, fit = meta["train"]["frame_statistics"], meta["train"]["variation"]
    assert stats["n_frames"] == fit["fit_parts"] and fit["data"] == "data/line-ef-train"  # make-model.sh's DATA
    # the metal plug mirrors the panel at full scale in more than a quarter of the panel line's good parts; the
    # dome line's range had clipped_fraction 0.00003 at its third quartile
    assert stats["q3"]["clipped_fraction"] > 0.01


def test_make_model_varies_the_panel_in_training_and_validation_only(tmp_path: Path) -> None:
    """Rule 52: the sets the shipped model is fitted, calibrated and thresholded on draw the panel's radiance per part
    (sim/presets/panel-vary.toml, after the panel itself); rules 62-63: the sets it is fitted and calibrated on also
    draw the plastic's finish wider (sim/presets/finish-vary.toml, last), and its threshold is set on the same
    validation parts with the finish as built; rule 67: those two sets also draw each part's edges (--edge-mm 0,0.4),
    the threshold's and the held-out set have the sharp edges as built. The held-out set is the line as built. The
    defaults name the sets the shipped sidecar records (with one draw of the look, LOOK_DRAWS=1: the shipped file is
    the draw thresholded so)."""
    import json

    calls = dry_run(tmp_path, LOOK_DRAWS="1")
    renders = [args for args in calls if args[0] == "render"]
    configs = {args[args.index("--out") + 1]: [args[i + 1] for i, a in enumerate(args) if a == "--config"]
               for args in renders}
    seeds = {args[args.index("--out") + 1]: args[args.index("--seed") + 1] for args in renders}
    assert len(renders) == 10  # five sets (the last: step 9's new kinds), two shards each
    vary, finish = "sim/presets/panel-vary.toml", "sim/presets/finish-vary.toml"
    train = json.loads((ROOT / "model" / "weights" / "default.json").read_text())["train"]
    fit, look, threshold = train["variation"], train["residual"], train["threshold_set"]
    assert configs[fit["data"]][-3:] == ["sim/presets/panel.toml", vary, finish]
    assert configs[fit["calibration_data"]][-3:] == ["sim/presets/panel.toml", vary, finish]
    assert look["calibration_data"] == fit["calibration_data"] and look["data"] == fit["data"]
    assert configs[threshold["data"]][-2:] == ["sim/presets/panel.toml", vary]
    assert seeds[threshold["data"]] == seeds[fit["calibration_data"]]  # the same parts, the finish as built
    assert configs["data/line-panel-heldout"][-1] == "sim/presets/panel.toml"
    edges = {out: a[a.index("--edge-mm") + 1] if "--edge-mm" in a else None
             for out, a in ((args[args.index("--out") + 1], args) for args in renders)}
    assert edges[fit["data"]] == edges[fit["calibration_data"]] == "0,0.4"
    assert edges[threshold["data"]] is None and edges["data/line-panel-heldout"] is None
    shipped = [args[args.index("--data") + 1] for args in calls
               if args[0] == "threshold" and args[args.index("--model") + 1].endswith("runs/band-look")]
    assert shipped == [threshold["data"]]


def test_make_model_judges_the_shipped_model_on_kinds_nobody_rendered(tmp_path: Path) -> None:
    """Step 9: a held-out set of the line as built with only the kinds no training draws (sim/presets/new-kinds.toml,
    last; its own seed), the shipped model evaluated on it with the line's validation thresholds; NEW_KINDS_COUNT=0
    skips both."""
    calls = dry_run(tmp_path)
    renders = {args[args.index("--out") + 1]: args for args in calls if args[0] == "render"}
    configs = {out: [a[i + 1] for i, x in enumerate(a) if x == "--config"] for out, a in renders.items()}
    seeds = {out: a[a.index("--seed") + 1] for out, a in renders.items()}
    assert configs["data/new-kinds-heldout"] == [*configs["data/line-panel-heldout"], "sim/presets/new-kinds.toml"]
    assert seeds["data/new-kinds-heldout"] not in {s for out, s in seeds.items() if out != "data/new-kinds-heldout"}
    assert "--heldout" in renders["data/new-kinds-heldout"]
    judged = [a for a in calls if a[0] == "eval" and a[a.index("--data") + 1] == "data/new-kinds-heldout"]
    assert len(judged) == 1 and judged[0][judged[0].index("--model") + 1] == str(tmp_path / "runs/band-look")
    assert judged[0][judged[0].index("--val-data") + 1] == "data/line-pv-val"
    kinds = tomllib.loads((ROOT / "sim/presets/new-kinds.toml").read_text())["defects"]["types"]
    assert tuple(kinds) == NEW_KINDS and not set(kinds) & set(DEFECT_TYPES)
    (tmp_path / "skip").mkdir()
    skipped = dry_run(tmp_path / "skip", NEW_KINDS_COUNT="0")
    assert not [a for a in skipped if "data/new-kinds-heldout" in a]



def test_make_model_times_each_command_and_prints_the_sum(tmp_path: Path) -> None:
    """Every command's wall seconds go to RUNS/timings.tsv (seconds, command, its output, when it ended) and the
    last lines sum them per command: how long the recipe took on this machine, across resumed runs too."""
    calls = dry_run(tmp_path, NEW_KINDS_COUNT="0", LOOK_DRAWS="1")
    rows = [line.split("\t") for line in (tmp_path / "runs" / "timings.tsv").read_text().splitlines()]
    others = [c for c in calls if c[0] != "render"]  # a render is two shards (JOBS=2), timed as one step
    # one row per command (the looks, their finishing and the evaluations run two at a time: in any order)
    assert len(rows) == len(others) + 4 and sorted(r[1] for r in rows[4:]) == sorted(c[0] for c in others)
    assert [r[1] for r in rows[:4]] == ["render"] * 4 and all(r[0].isdigit() for r in rows)
    outputs = {(r[1], r[2]) for r in rows}
    assert ("render", "data/line-ef-train") in outputs and ("residual", str(tmp_path / "runs/band-look")) in outputs
    assert ("threshold", str(tmp_path / "runs/band-look")) in outputs  # no --out: its --model


def test_a_failing_step_stops_make_model_even_where_its_command_is_skipped_when_done(tmp_path: Path) -> None:
    """The variation fit runs as `[ -f done ] || station variation ...` through the timing function: a failed
    fit stops the script (no timing line, no look network trained on nothing)."""
    rc, lines = stub_run(tmp_path, 'echo "$*" >> "$CALLS"\n[ "$1" != variation ]\n')
    assert rc != 0
    assert lines[-1].startswith("variation")  # nothing ran after the failed fit
    assert "\tvariation\t" not in (tmp_path / "runs" / "timings.tsv").read_text()


def timed_looks(tmp_path: Path, fail: str = "", **env_vars: str) -> tuple[int, list[str]]:
    """make-model.sh with a `station` whose look networks take half a second (and the one without type ``fail``
    fails): its return code and the lines "start T", "end T" (T the type left out, "-" for the shipped look) and
    the other commands, in the order they happened. One draw of the shipped look (LOOK_DRAWS=1) unless ``env_vars``
    say otherwise."""
    return stub_run(tmp_path, """t=$(echo "$*" | sed -n 's/.*--holdout-type \\([a-z_]*\\).*/\\1/p')
if [ "$1" = residual ]; then
    t=${t:--}
    echo "start $t" >> "$CALLS"; sleep 0.5; echo "end $t" >> "$CALLS"; [ "$t" != "$FAIL" ]
else
    echo "$1" >> "$CALLS"
fi
""", FAIL=fail, NEW_KINDS_COUNT="0", **({"LOOK_DRAWS": "1"} | env_vars))


def test_make_model_trains_the_look_networks_two_at_a_time(tmp_path: Path) -> None:
    """The look networks of steps 6b and 7 train on one thread each: JOBS of them at once (two, one per core), never
    more, and every one has finished before any is thresholded."""
    rc, lines = timed_looks(tmp_path)
    assert rc == 0
    running, most = 0, 0
    for line in lines:
        running += line.startswith("start ") - line.startswith("end ")
        most = max(most, running)
    assert most == 2 and sorted(x for x in lines if x.startswith("start ")) == [
        "start -", "start chip", "start dent", "start missing_stud", "start scratch", "start stain"]
    last_end = max(i for i, line in enumerate(lines) if line.startswith("end "))
    first_start = min(i for i, line in enumerate(lines) if line.startswith("start "))
    assert "threshold" not in lines[first_start:last_end] and "threshold" in lines[last_end:]
    (tmp_path / "one").mkdir()
    rc, lines = timed_looks(tmp_path / "one", JOBS="1")
    assert rc == 0 and all(b == "end " + a.removeprefix("start ")
                           for a, b in itertools.pairwise(lines) if a.startswith("start "))


def test_a_failed_held_out_look_stops_make_model(tmp_path: Path) -> None:
    """A look trained in the background that fails stops the recipe: nothing is thresholded or evaluated after it
    (the look beside it may finish: its file is kept for the rerun)."""
    rc, lines = timed_looks(tmp_path, fail="scratch")
    assert rc != 0 and "end scratch" in lines
    after = lines[lines.index("end scratch"):]
    assert "eval" not in after and "threshold" not in after


def test_make_model_trains_the_networks_on_every_core_and_the_rest_on_one_thread(tmp_path: Path) -> None:
    """The networks train with nothing beside them: TRAIN_THREADS (JOBS, 2) threads, 1.6x one thread's speed
    (docs/results/2026-12-03-recipe-time.md); every other command runs on one thread beside another process."""
    rc, lines = stub_run(tmp_path, 'echo "$1 $OMP_NUM_THREADS" >> "$CALLS"\n', NEW_KINDS_COUNT="0",
                         OMP_NUM_THREADS="")
    assert rc == 0
    threads = [line.split() for line in lines]
    assert [t for c, t in threads if c == "train"] == ["2"]  # the shell (the test below)
    assert {t for c, t in threads if c != "train"} == {"1"} and len(threads) > 20
    (tmp_path / "combined").mkdir()
    rc, lines = stub_run(tmp_path / "combined", 'echo "$1 $OMP_NUM_THREADS" >> "$CALLS"\n', NEW_KINDS_COUNT="0",
                         OMP_NUM_THREADS="", DECISION="combined")
    assert rc == 0 and [t for c, t in (line.split() for line in lines) if c == "train"] == ["2"] * 8


def test_make_model_trains_only_a_shell_of_the_networks_that_do_not_decide(tmp_path: Path) -> None:
    """With the shipped decision (the variation model and its look) the DRAEM networks decide nothing, so make model
    trains one band network of SHELL_STEPS steps from nothing (it carries the priors, the band and the input size),
    fits the variation model on it and neither thresholds nor evaluates it; with the networks deciding, the base,
    mixed and band networks are trained whole and each is evaluated."""
    calls = dry_run(tmp_path, NEW_KINDS_COUNT="0")
    trained = [a for a in calls if a[0] == "train"]
    assert len(trained) == 1 and out_name(trained[0], tmp_path) == "band" and "--init" not in trained[0]
    assert trained[0][trained[0].index("--steps") + 1] == "30" and "--roi" in trained[0]
    fit = next(a for a in calls if a[0] == "variation")
    assert fit[fit.index("--model") + 1] == str(tmp_path / "runs/band/last")
    judged = {out_name(a, tmp_path) for a in calls if a[0] in ("eval", "threshold")}
    assert not judged & {"base/last", "eval-base", "eval-mixed", "eval-band"}
    assert {"eval-band-variation", "eval-band-look"} <= judged
    (tmp_path / "combined").mkdir()
    calls = dry_run(tmp_path / "combined", NEW_KINDS_COUNT="0", DECISION="combined")
    assert [out_name(a, tmp_path / "combined") for a in calls if a[0] == "train"][:3] == ["base", "mixed", "band"]
    fit = next(a for a in calls if a[0] == "variation")
    assert fit[fit.index("--model") + 1] == str(tmp_path / "combined/runs/band/best")
    assert {"eval-base", "eval-mixed", "eval-band"} <= {out_name(a, tmp_path / "combined") for a in calls}


def test_make_model_priors_reach_every_network(tmp_path: Path) -> None:
    """PRIORS=intensity (docs/results/2026-12-04-intensity-robust.md): every network make model trains reads the
    priors asked for, and by default the shipped file's intensity alone."""
    for env, want in (({}, "intensity"), ({"PRIORS": "intensity,dolp,aolp"}, "intensity,dolp,aolp")):
        runs = tmp_path / (want.replace(",", "-"))
        runs.mkdir()
        trained = [a for a in dry_run(runs, **env) if a[0] == "train"]
        assert trained and {a[a.index("--priors") + 1] for a in trained} == {want}


def test_an_empty_base_stop_runs_the_base_schedule_whole(tmp_path: Path) -> None:
    """BASE_STOP= (empty) runs the base network's whole schedule, as the script says; unset, it stops at step 500.
    An empty value fell back to 500, so a short smoke run (BASE_STEPS=4) was refused. (The base is trained when the
    networks decide.)"""
    for case in ("empty", "unset"):
        (tmp_path / case).mkdir()
    whole = [a for a in dry_run(tmp_path / "empty", empty=("BASE_STOP",), DECISION="combined")
             if a[0] == "train" and "base" in " ".join(a)]
    assert whole and "--stop-at-step" not in whole[0]
    unset = [a for a in dry_run(tmp_path / "unset", BASE_STOP="", DECISION="combined")  # "" unsets it
             if a[0] == "train"]
    assert unset[0][unset[0].index("--stop-at-step") + 1] == "500"


def test_make_model_region_reaches_every_network(tmp_path: Path) -> None:
    """ROI and SIZE (model/draem/roi.py): every network make model trains on a region (all but the centre square's
    base and mixed networks of DECISION=combined) sees the one asked for, by default the shipped file's band at
    96 x 192."""
    for env, want in (({}, ("band", "96")), ({"ROI": "tall", "SIZE": "128"}, ("tall", "128")),
                      ({"ROI": "tall", "SIZE": "128", "DECISION": "combined"}, ("tall", "128"))):
        runs = tmp_path / "-".join(env.values() or ["default"])
        runs.mkdir()
        trained = [a for a in dry_run(runs, NEW_KINDS_COUNT="0", **env) if a[0] == "train" and "--roi" in a]
        assert trained and {(a[a.index("--roi") + 1], a[a.index("--size") + 1]) for a in trained} == {want}


def test_a_lens_preset_is_layered_last_on_the_fit_calibration_and_threshold_sets_only(tmp_path: Path) -> None:
    """``LENS=PRESET`` (docs/results/2026-12-08-lens-train/plan.md): the sets the model is fitted, calibrated and
    thresholded on draw the lens that preset names (``sim/presets/lens-vary.toml``: a blur and vignetting per part),
    layered last; the held-out and new-kinds sets stay the line as built. Unset, no render names it."""
    lens = "sim/presets/lens-vary.toml"
    assert (ROOT / lens).is_file()
    for env, want in (({}, False), ({"LENS": lens}, True)):
        (tmp_path / str(want)).mkdir()
        calls = dry_run(tmp_path / str(want), **env)
        renders = {args[args.index("--out") + 1]: args for args in calls if args[0] == "render"}
        configs = {out: [a[i + 1] for i, x in enumerate(a) if x == "--config"] for out, a in renders.items()}
        for out in ("data/line-ef-train", "data/line-ef-val", "data/line-pv-val"):
            assert (configs[out][-1] == lens) is want, out
        for out in ("data/line-panel-heldout", "data/new-kinds-heldout"):
            assert lens not in configs[out], out


def test_smooth_field_reaches_every_variation_fit_and_is_off_unset(tmp_path: Path) -> None:
    """``SMOOTH_FIELD=1`` (docs/results/2026-12-09-smooth-field/plan.md): every variation model make model fits takes
    a lens's smooth field out (``station variation --smooth-field``); unset, none is asked for (the shipped recipe)."""
    for env, want in (({}, False), ({"SMOOTH_FIELD": "1"}, True)):
        (tmp_path / str(want)).mkdir()
        fits = [args for args in dry_run(tmp_path / str(want), **env) if args[0] == "variation"]
        assert fits and all(("--smooth-field" in args) is want for args in fits)


def test_look_lens_reaches_every_look_network_and_is_off_unset(tmp_path: Path) -> None:
    """``LOOK_LENS=LO,HI`` (docs/results/2026-12-10-look-lens/plan.md): every look network make model trains, the
    held-out types' too, learns from lens copies of the good parts (``station residual --lens-copies``); unset, none
    does (the shipped recipe)."""
    for env, want in (({}, None), ({"LOOK_LENS": "0,0.3"}, "0,0.3")):
        (tmp_path / str(want)).mkdir()
        looks = [args for args in dry_run(tmp_path / str(want), **env) if args[0] == "residual"]
        assert looks and all((args[args.index("--lens-copies") + 1] if "--lens-copies" in args else None) == want
                             for args in looks)


def test_the_lens_preset_draws_a_blur_and_vignetting_per_part() -> None:
    """Its ranges are the plan's: a blur of 0-1 frame px and 0-30 % of the light lost at the frame's corners."""
    data = tomllib.loads((ROOT / "sim" / "presets" / "lens-vary.toml").read_text())
    assert data["variation"] == {"lens_blur_px": [0.0, 1.0], "vignetting": [0.0, 0.3]}


def test_look_draws_train_the_look_k_times_and_keep_the_one_a_lens_moves_least(tmp_path: Path) -> None:
    """``LOOK_DRAWS=3`` (docs/results/2026-12-11-look-draw/plan.md): the look trained with seeds 0, 1, 2, each
    blended and thresholded as the shipped look, then ``station pick`` keeps one as band-look on the validation parts
    rendered again through a lens drawn per part (the same seed and parts as VAL, lens-vary.toml layered last); the
    held-out types' looks stay one draw each. Three is the shipped recipe (unset); LOOK_DRAWS=1: one look, no lens
    set, no pick."""
    (tmp_path / "one").mkdir()
    calls = dry_run(tmp_path / "one", LOOK_DRAWS="1")
    assert not [a for a in calls if a[0] == "pick"]
    assert "data/line-pv-val-lens" not in [a[a.index("--out") + 1] for a in calls if a[0] == "render"]
    calls = dry_run(tmp_path)
    looks = {out_name(a, tmp_path): a for a in calls if a[0] == "residual"}
    draws = [f"band-look-draw-{n}" for n in range(3)]
    assert sorted(looks) == sorted([*draws, *(f"holdout-{t}" for t in ("dent", "scratch", "stain", "chip",
                                                                          "missing_stud"))])
    for n, name in enumerate(draws):
        assert looks[name][looks[name].index("--seed") + 1] == str(n)
    assert all("--seed" not in a for name, a in looks.items() if name.startswith("holdout-"))
    renders = {a[a.index("--out") + 1]: a for a in calls if a[0] == "render"}
    lens, val = renders["data/line-pv-val-lens"], renders["data/line-pv-val"]
    configs = [lens[i + 1] for i, x in enumerate(lens) if x == "--config"]
    assert configs[-1] == "sim/presets/lens-vary.toml" and configs[:-1] == [
        val[i + 1] for i, x in enumerate(val) if x == "--config"]
    for flag in ("--seed", "--count", "--defects"):
        assert lens[lens.index(flag) + 1] == val[val.index(flag) + 1]
    assert "--validation" in lens
    (pick,) = [a for a in calls if a[0] == "pick"]
    models = pick[pick.index("--models") + 1:pick.index("--data")]
    assert models == [str(tmp_path / "runs" / d) for d in draws]
    assert pick[pick.index("--data") + 1] == "data/line-pv-val-lens" and out_name(pick, tmp_path) == "band-look"
    finished = [out_name(a, tmp_path) for a in calls[:calls.index(pick)] if a[0] == "threshold"]
    assert set(draws) <= set(finished)  # each draw at its own threshold before the choice
    after = calls[calls.index(pick):]
    assert any(a[0] == "eval" and a[a.index("--model") + 1] == str(tmp_path / "runs/band-look") for a in after)
