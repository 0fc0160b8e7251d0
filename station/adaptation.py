"""``station adapt`` behind the parser: load a model and the good parts of a line's set, run the model-side policy
(``model.draem.adapt``), write the adapted checkpoint with a record of what it was adapted on."""

from __future__ import annotations

import hashlib
import time
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any

from model.draem.config import GOOD_REJECTED_RATE
from station.config import PRESENCE_RULES
from station.errors import UserError


@dataclass
class AdaptSummary:
    out: Path
    record: dict[str, Any]

    def describe(self) -> str:
        from station.evaluation import describe_left_out, new_good_rate

        r = self.record
        held = new_good_rate(r["n_heldout_rejected"], r["n_heldout"])
        return (f"{self.out}: adapted on {r['n_good']} good parts of {r['data']} ({r['scheme']}); threshold "
                f"{r['threshold']:.4g}, {100 * r['heldout_false_reject']:.1f} % of held-out good parts rejected "
                f"({held}; target {100 * r['false_reject_target']:.1f} %){self._networks()}; frames: "
                f"{r['frame_statistics']}"
                + (f"\nleft out {len(r['left_out'])} frames the station would not judge: "
                   f"{describe_left_out(r['left_out'])}" if r.get("left_out") else "")
                + (f"\n{r['shape']}" if r.get("shape") else "")
                + (f"\nnote: {r['advice']}" if r.get("advice") else ""))

    def _networks(self) -> str:
        shift = self.record.get("networks_shift_sd")
        if shift is None:
            return ""
        if self.record.get("decision") == "variation" and not self.record.get("decision_changed", True):
            return (f"; it decides on the variation model alone, as the model did (networks' good parts "
                    f"{shift:.1f} robust SD from their validation parts, reported only)")
        if self.record.get("decision") == "variation":
            return (f"; the networks are out of their domain here (good parts {shift:.1f} robust SD above their "
                    f"validation parts): it decides on the variation model alone (--keep-networks keeps them)")
        return f"; networks' good parts {shift:.1f} robust SD from their validation parts (kept)"


def frames_sha256(root: str | Path, indices: list[int]) -> str:
    """sha256 over the raw mosaic files of samples ``indices`` of set ``root``, in that order."""
    from sim.dataset import sample_dir

    h = hashlib.sha256()
    for i in indices:
        h.update((sample_dir(root, i) / "raw.png").read_bytes())
    return h.hexdigest()


def adapt_model(model: str, good: str, out: str, split: str = "train", limit: int | None = None,
                false_reject: float = GOOD_REJECTED_RATE, fine_tune_steps: int = 0, seed: int = 0,
                keep_networks: bool = False, presence_rule: str = PRESENCE_RULES[0],
                floor_checks: bool | None = None) -> AdaptSummary:
    """Adapt checkpoint ``model`` to the good parts of ``good``'s ``split`` (at most ``limit``), write ``out``; the
    frames the station would not judge, with the presence check's ``presence_rule`` at its defaults, left out;
    ``floor_checks`` None: ``AdaptConfig``'s default."""
    from model.draem.adapt import AdaptConfig, adapt
    from model.draem.checkpoint import load_checkpoint, paths, save_checkpoint
    from model.priors.frame_stats import StatisticsRange
    from station.datasets import judged_part_of, manifest_sha256
    from station.evaluation import describe_left_out, model_split
    from station.presence import PresenceCheck

    if paths(out)[1].resolve() == paths(model)[1].resolve():
        raise UserError(f"--out {out}: the same checkpoint as --model; write the adapted model beside it")
    cfg = AdaptConfig(false_reject=false_reject, fine_tune_steps=fine_tune_steps, seed=seed,
                      keep_networks=keep_networks)
    if floor_checks is not None:
        cfg = replace(cfg, floor_checks=floor_checks)
    ck = load_checkpoint(model)
    sp, left_out = judged_part_of(model_split(ck, model, good, split, limit,
                                              presence=PresenceCheck(rule=presence_rule)))
    keep = (sp.label == 0).nonzero().flatten()
    if len(keep) == 0:
        raise UserError(f"{good}: split {split!r} has no good parts the station would judge"
                        + (f" ({describe_left_out(left_out)})" if left_out else ""))
    x, obj = sp.priors[keep], sp.object_mask[keep]
    det, res = adapt(ck.detector, x, obj, cfg, around=None if sp.around is None else sp.around[keep])
    used = [sp.index[int(k)] for k in keep]
    stats = StatisticsRange.from_frames([sp.frame_stats[int(k)] for k in keep])
    record = {**res.record(), "data": str(good), "split": split, "manifest_sha256": manifest_sha256(good),
              "frames_sha256": frames_sha256(good, used), "date": time.strftime("%Y-%m-%dT%H:%M:%S"),
              "false_reject_target": false_reject, "base_model": str(model),
              "left_out": {str(i): why for i, why in left_out.items()}, "presence_rule": str(presence_rule),
              "base_weights_sha256": ck.meta.get("weights_sha256"), "frame_statistics": stats.describe()}
    train = {**ck.meta.get("train", {}), "adapted": record, "frame_statistics": stats.to_dict()}
    save_checkpoint(out, det, res.threshold.threshold, res.threshold.rule, ck.meta.get("data_manifest_sha256"),
                    {}, train)
    from model.normals.estimator import copy_beside

    copy_beside(paths(model)[1], paths(out)[1], train.get("normal_prior"))  # a learned normal prior's estimator
    return AdaptSummary(Path(out), record)
