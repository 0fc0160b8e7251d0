"""What a lower threshold wins on the validation set (docs/results/2026-12-06-visible-auroc.md; development reading).

The shipped file on ``data/line-pv-val``'s val split: each part's variation score (``member_scores["variation"]``);
the good parts with the highest, with the angle between the stray lamp and the camera's mirror direction in the top
face (from each part's rendered scene); then, at a range of thresholds on that score, the defective parts caught (per
type) and the good parts over it. Run from the repository's root."""

import json

import numpy as np
import torch

from model.draem.checkpoint import load_checkpoint
from station.evaluation import model_split

MODEL, DATA = "model/weights/default", "data/line-pv-val"
ck = load_checkpoint(MODEL)
det = ck.detector.eval()
sp = model_split(ck, MODEL, DATA, "val")
x, label, types = sp.priors.float(), sp.label.numpy() == 1, np.array(sp.defect_type)
with torch.no_grad():
    v = np.concatenate([det.predict(x[b:b + 16]).member_scores["variation"].numpy() for b in range(0, len(x), 16)])


def lamp_angle(i: int) -> float:
    """Degrees between the stray lamp's direction and the camera ray mirrored in a level top face."""
    p = json.load(open(f"{DATA}/samples/{i:06d}/params.json"))["scene"]
    c, t = np.array(p["camera"]["origin"]), np.array(p["camera"]["target"])
    r = (t - c) * [1, 1, -1]
    lamp = np.array(p["light"]["origin"]) - t
    return float(np.degrees(np.arccos(np.clip(r @ lamp / np.linalg.norm(r) / np.linalg.norm(lamp), -1, 1))))


good = np.flatnonzero(~label)
print(f"{len(good)} good, {int(label.sum())} defective parts\nhighest good parts (variation score, lamp angle deg):")
for i in good[np.argsort(-v[good])][:8]:
    print(f"  part {sp.index[i]}: {v[i]:.2f}, {lamp_angle(sp.index[i]):.1f}")
print("\n| threshold | defective caught | " + " | ".join(sorted(set(types[label]))) + " | good over |")
print("|---|---|" + "---|" * len(set(types[label])) + "---|")
for t in (np.sort(v[good])[-4], 11.16, 9.35, 8.0, 7.0, 6.0):
    c = label & (v > t)
    print(f"| {t:.2f} | {int(c.sum())} | " + " | ".join(str(int((c & (types == k)).sum()))
                                                       for k in sorted(set(types[label])))
          + f" | {int((~label & (v > t)).sum())} |")
print(f"\ndefective parts not caught at the 4th highest good part: variation median "
      f"{np.median(v[label & (v <= np.sort(v[good])[-4])]):.2f}; good parts' median {np.median(v[good]):.2f}")
