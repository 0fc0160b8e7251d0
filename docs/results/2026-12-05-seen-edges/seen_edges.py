"""Does the outline check reading no column from pixels the registration made up win back the good parts a turned
camera costs, and does it change anything else? (docs/results/2026-12-05-seen-edges.md)

Each argument is a set and its split (`data/line-1204-turned5:test`). On each set, the shipped file judges every
part twice on the same priors: `before`, its outline check reading every column of the registered frame as the file
did until this change (the border the warp replicated included), and `after`, reading only the seen columns
(`VariationModel.checked_intensity`). Prints per set and arm the good parts rejected, the defective parts caught
(all and per kind), each part whose decision the two arms differ on, and each good part an arm rejects with what
rejected it (window score, shape check's bend, outline check's step, each over its own threshold: above 1
rejects). Run from the repository's root."""

import sys

import numpy as np
import torch

from model.draem.adapt import image_scores
from model.draem.checkpoint import load_checkpoint
from station.evaluation import model_split

MODEL = "model/weights/default"
ck = load_checkpoint(MODEL)
det, thr = ck.detector, ck.threshold
var = det.variation


def unchecked(aligned: tuple[np.ndarray, ...]) -> np.ndarray:
    """The outline check's input before this change: every pixel of the registered intensity."""
    return aligned[0][var.intensity]


for arg in sys.argv[1:]:
    path, split = arg.split(":")
    sp = model_split(ck, MODEL, path, split)
    x = sp.priors.float()
    lab = sp.label.numpy() == 1
    kinds = np.array([sp.defect_type[i] or "" for i in range(len(lab))])
    names = sorted(set(kinds[lab]))
    print(f"\n## {path} ({split}): {int((~lab).sum())} good, {int(lab.sum())} defective "
          f"({', '.join(f'{k} {int((kinds[lab] == k).sum())}' for k in names)})", flush=True)
    rejected = {}
    for arm in ("before", "after"):
        if arm == "before":
            var.checked_intensity = unchecked  # type: ignore[method-assign]
        else:
            del var.checked_intensity
        s = image_scores(det, x)
        rej = s > thr
        rejected[arm] = rej
        per = " | ".join(f"{int(rej[lab & (kinds == k)].sum())}/{int((lab & (kinds == k)).sum())}" for k in names)
        print(f"| {arm} | {int(rej[~lab].sum())} of {int((~lab).sum())} good rejected | {int(rej[lab].sum())} of "
              f"{int(lab.sum())} defective caught ({100 * rej[lab].mean():.1f} %) | {per} |", flush=True)
        which = np.flatnonzero(rej & ~lab)
        if len(which):
            out = var.zmaps(x[torch.from_numpy(which)])
            for k, i in enumerate(which):
                print(f"  {arm}: good part {int(i)} score {s[i]:.4f}; window {float(out.scores[k]):.3f}, "
                      f"bend {float(out.edge_bend[k]):.3f}, step {float(out.edge_step[k]):.3f}")
    differ = np.flatnonzero(rejected["before"] != rejected["after"])
    print(f"decisions that differ: {len(differ)}" + "".join(
        f"\n  part {int(i)} ({kinds[i] or 'good'}): before {'reject' if rejected['before'][i] else 'pass'}, after "
        f"{'reject' if rejected['after'][i] else 'pass'}" for i in differ))
