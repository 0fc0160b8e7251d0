"""Screen: how the look's members are joined, from dump.py's per-member top logits: each draw alone, their mean (a
`--members 3` look), their median, their minimum (a finding the members agree on) and each pair's mean. Each joined
look calibrated as `station residual` does (calibration set's good parts), blended and thresholded as `station
blend` and `station threshold` do (validation set's good parts, 1 %). Prints good parts rejected and defective caught
at that threshold on every dumped set, and [caught at matched rates of 1, 2 and 5 %, averaged].
Usage: aggregate.py DUMP_DIR MODEL (the file dumped; its variation model's units and blend weight are read)."""

import sys
from pathlib import Path

import numpy as np
import torch

from model.draem.checkpoint import load_checkpoint
from model.draem.metrics import false_reject_threshold as frt
from model.draem.residual import blended
from model.draem.second_look import robust_location_spread

JOINS = {"m0": lambda lg: lg[:, 0], "m1": lambda lg: lg[:, 1], "m2": lambda lg: lg[:, 2],
         "mean": lambda lg: lg.mean(1), "median": lambda lg: np.median(lg, 1), "min": lambda lg: lg.min(1),
         "m0+m1": lambda lg: lg[:, [0, 1]].mean(1), "m0+m2": lambda lg: lg[:, [0, 2]].mean(1),
         "m1+m2": lambda lg: lg[:, [1, 2]].mean(1)}


class Joined:
    """The dumped sets of one file (``calib`` and ``val`` among them) and the file's look units and blend weight."""

    def __init__(self, dump: Path, model: str) -> None:
        det = load_checkpoint(model).detector
        self.look = det.variation.second_look
        self.weight = float(det.residual.blend[0])
        self.sets = {p.stem: dict(np.load(p)) for p in sorted(Path(dump).glob("*.npz"))}

    def calibrate(self, join):
        """The look's units (calibration set) and the blend's thresholds (validation set) of ``join``."""
        c, v = self.sets["calib"], self.sets["val"]
        g, gv = c["label"] == 0, v["label"] == 0
        lg = JOINS[join](c["logits"][g])
        loc, spread = robust_location_spread(lg)
        t = frt((lg - loc) / spread, 0.01)
        tv = frt(self.look.window_sd(c["score"][g]), 0.01)
        found = self.look.from_window_sd((JOINS[join](v["logits"][gv]) - loc) / spread / t * tv)
        return loc, spread, t, tv, frt(v["score"][gv], 0.01), frt(found, 0.01)

    def scores(self, join):
        """Per set, each part's blended score (window units; a part the station would not judge: inf) and the
        threshold (1 % of the validation set's good parts)."""
        loc, spread, t, tv, t_w, t_f = self.calibrate(join)
        out = {}
        for name, s in self.sets.items():
            found = self.look.from_window_sd((JOINS[join](s["logits"]) - loc) / spread / t * tv)
            b = blended(torch.from_numpy(s["score"]), torch.from_numpy(s["window"]), torch.from_numpy(found),
                        self.weight, t_w, t_f).numpy()
            out[name] = np.where(s["unjudged"], np.inf, b)
        return out, frt(out["val"][self.sets["val"]["label"] == 0], 0.01)


def matched(s: np.ndarray, label: np.ndarray, rates=(1, 2, 5)) -> float:
    """Defective caught (%) at matched rates of the set's good parts, averaged over ``rates`` (%)."""
    g, d = label == 0, label == 1
    out = []
    for k in rates:
        q = np.sort(s[g])[::-1][int(np.floor(g.sum() * k / 100))]
        out.append((s[d] > q).mean() * 100)
    return float(np.mean(out))


def main(dump: str, model: str, joins=tuple(JOINS)) -> None:
    jd = Joined(Path(dump), model)
    for join in joins:
        sc, thr = jd.scores(join)
        line = [f"{join:6s}"]
        for name in jd.sets:
            if name == "calib":
                continue
            s, lab = sc[name], jd.sets[name]["label"]
            g, d = lab == 0, lab == 1
            rate = [f"{name} {int((s[g] > thr).sum())}/{int(g.sum())}"]
            if d.any() and name != "vallens":
                rate += [f"{(s[d] > thr).mean() * 100:.1f}%", f"[{matched(s, lab):.1f}]"]
            line.append(" ".join(rate))
        print("  ".join(line))


if __name__ == "__main__":
    main(*sys.argv[1:3])
