"""Screen: the look networks of several draws (trainings of one recipe on one variation model) joined as the members
of one look, calibrated as `station residual` calibrates a look (on CALIBRATION's good val parts), written without
its shape check, blend or threshold (make model's `finish` adds them). Usage: join.py BASE CALIBRATION OUT DRAW...
(BASE: the variation model the draws were trained on, e.g. runs/make-model-draw/band-variation)."""

import sys

import torch

from model.draem.checkpoint import load_checkpoint, save_checkpoint
from model.draem.detector import Detector
from model.draem.with_variation import calibrate_look, residual_raw
from station.evaluation import model_split

base_path, calib, out_path, *draws = sys.argv[1:]
base = load_checkpoint(base_path)
looks = [load_checkpoint(d) for d in draws]
members = sum(len(lk.detector.residual.members) for lk in looks)
det = Detector(base.detector.config.with_(residual_members=members), base.detector.normalizer)
missing, unexpected = det.load_state_dict(base.detector.state_dict(), strict=False)
assert not unexpected and all(k.startswith("residual.") for k in missing), (missing, unexpected)
k = 0
for lk in looks:
    for net in lk.detector.residual.members:
        det.residual.members[k].load_state_dict(net.state_dict())
        k += 1
det.eval()
va = model_split(base, base_path, calib, "val", good_only=True)
print(f"{calib}: {len(va.priors)} good val parts; {members} members", file=sys.stderr, flush=True)
with torch.no_grad():
    det.residual.calibrate(residual_raw(det, va.priors))
    calibrate_look(det, va.priors)
det.variation.check()
det.residual.check()
train = dict(base.meta.get("train", {}))
train["residual"] = {**looks[0].meta["train"]["residual"], "members": members, "joined": list(draws)}
save_checkpoint(out_path, det, threshold=base.meta.get("threshold"), threshold_rule=base.meta.get("threshold_rule", ""),
                data_manifest_sha256=base.meta.get("data_manifest_sha256"), train=train)
print(out_path)
