"""B for plan.md: the checkpoint at sys.argv[1] (a copy of the shipped file) rewritten in place with its outline check
switched off (``OutlineCheck.clear``): every other tensor, the threshold and the sidecar's record as they were, the
outline's record None. The file before stop 106 was this (its outline buffers unset)."""

import sys

from model.draem.checkpoint import load_checkpoint, save_checkpoint

path = sys.argv[1]
ck = load_checkpoint(path)
if ck.detector.variation.outline.fitted:
    ck.detector.variation.outline.clear()
    meta = ck.meta
    train = meta.get("train", {})
    save_checkpoint(path, ck.detector, ck.threshold, meta.get("threshold_rule", ""), meta.get("data_manifest_sha256"),
                    meta.get("metrics"), {**train, "shape": {**train.get("shape", {}), "outline": None}})
print(f"{path}: outline check {'on' if load_checkpoint(path).detector.variation.outline.fitted else 'off'}")
