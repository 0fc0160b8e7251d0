"""Add the training split's defective parts and every scored part's defect mask warped to the reference."""

from __future__ import annotations

import copy
import sys

import numpy as np
from spies import JUD, RES, install

from model.draem.checkpoint import load_checkpoint
from model.draem.variation import MAX_HIDDEN
from station.datasets import load_split

PRIORS = ("intensity", "dolp", "aolp")
SHAPE = (96, 192)
train_dir, val_dir, held_dir, out = sys.argv[1:5]
st = load_split(train_dir, "train", PRIORS, SHAPE, roi="band", progress=False, good_only=True)
m = copy.deepcopy(load_checkpoint("model/weights/default").detector.variation)
m.fit(st.priors.float(), st.object_mask)
install()
scale, ref = m.scale.numpy(), m.reference.numpy()


def warped_masks(x, masks):
    out = []
    for xi, mi in zip(x.float().numpy(), masks, strict=True):
        peak = m.peak(xi)
        seen = ~m.highlight(peak)
        w = m.warp_to(
            ref,
            np.concatenate([m.features(xi), peak[None], mi[None].astype(np.float32)]),
            seen if seen.mean() > 1.0 - MAX_HIDDEN else None,
        )
        out.append(w[-1] > 0.5)
    return np.stack(out)


d = {}
for tag, root, split in (("trdef", train_dir, "train"), ("val", val_dir, "val"), ("held", held_dir, "test")):
    s = load_split(root, split, PRIORS, SHAPE, roi="band", progress=False)
    keep = np.where(s.label.numpy() > 0)[0] if tag == "trdef" else np.arange(len(s.label))
    x = s.priors.float()[keep]
    mk = s.defect_mask.numpy()[keep].astype(bool)
    d[f"{tag}_wmask"] = warped_masks(x, mk)
    if tag == "trdef":
        RES.clear()
        JUD.clear()
        for i in range(0, len(x), 50):
            m.zmaps(x[i : i + 50])
        d["trdef_z"] = np.stack([m.used(r[0] / scale) for r in RES]).astype(np.float16)
        d["trdef_judged"] = np.stack(JUD)
        d["trdef_type"] = np.array([s.defect_type[i] or "" for i in keep])
    print(tag, len(keep), flush=True)
np.savez(out, **d)
