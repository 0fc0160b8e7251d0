"""Per part of a set, what each file's look blend reads (../2026-12-12-look-ensemble/dump.py's arrays), for several
files of one input size, the set loaded once. Usage: dump.py SET SPLIT NAME MODEL=OUT_DIR... (writes
OUT_DIR/NAME.npz for each)."""

import sys
from pathlib import Path

import numpy as np
import torch

from model.draem.checkpoint import load_checkpoint
from model.draem.residual import TOP_K
from model.draem.with_variation import rows
from station.evaluation import model_split

data, split, name, *pairs = sys.argv[1:]
files = [p.split("=", 1) for p in pairs]
cks = [load_checkpoint(m) for m, _ in files]
assert len({ck.detector.config.input_shape for ck in cks}) == 1, "one input size per call"
sp = model_split(cks[0], files[0][0], data, split)
for ck, (_, out) in zip(cks, files, strict=True):
    det = ck.detector
    scores, windows, logits = [], [], []
    with torch.no_grad():
        for i in range(0, len(sp.priors), 16):
            v = det.variation.zmaps(sp.priors[i:i + 16], signed=True, around=rows(sp.around, i, 16))
            x, j = det.residual_inputs(v.signed, v.judged)
            j = j.bool() | ~j.flatten(1).any(1).view(-1, 1, 1)
            k = min(TOP_K, j[0].numel())
            logits.append(torch.stack([m(x).masked_fill(~j, -torch.inf).flatten(1).topk(k, 1).values.mean(1)
                                       for m in det.residual.members], 1).double().numpy())
            scores.append(v.scores.double().numpy())
            windows.append(v.maps.flatten(1).amax(1).double().numpy())
    Path(out).mkdir(parents=True, exist_ok=True)
    np.savez(Path(out) / f"{name}.npz", score=np.concatenate(scores), window=np.concatenate(windows),
             logits=np.concatenate(logits), label=sp.label.numpy(), defect_type=np.array(sp.defect_type),
             index=np.array(sp.index),
             unjudged=np.array([u is not None for u in sp.unjudged]) if sp.unjudged else np.zeros(len(sp.label), bool))
    print(out, name, len(sp.label))
