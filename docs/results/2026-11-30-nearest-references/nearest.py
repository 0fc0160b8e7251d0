"""Validation screen (stop 65): each place's reference taken from the K calibration good parts most like the part,
not from all of them: neighbours by the window statistic at a coarse scale (what a station could compute), or by
the true stray-light vector (intensity times direction, from params.json: the best a stray-light estimate could do),
with or without the part's true pose.

Reads runs/a64/w-pf.npz (calibration, data/line-pf-val) and w-pv.npz (screen, data/line-pv-val), written by
../2026-11-30-place-tail/windows.py. Usage (repository root):
python docs/results/2026-11-30-nearest-references/nearest.py
"""

import json

import numpy as np

from model.draem.metrics import auroc, caught_at_false_reject

COARSE = 8  # px per cell of the coarse map (12 x 24 cells)


def load(name: str) -> dict:
    d = np.load(f"runs/a64/w-{name}.npz")
    return {k: d[k] for k in d}


def light_and_pose(data: str, index: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(N, 3) each sample's stray-light intensity times its unit direction (towards the lamp), and (N, 3) its pose on
    the belt, yaw (rad) and x, y (m); from its params.json."""
    light, pose = [], []
    for i in index:
        scene = json.load(open(f"data/{data}/samples/{i:06d}/params.json"))["scene"]
        p, q = scene["light"], scene["pose"]
        d = np.array(p["origin"]) - np.array(p["target"])
        light.append(p["intensity"] * d / np.linalg.norm(d))
        pose.append([q["yaw_rad"], *q["xy_m"]])
    return np.array(light), np.array(pose)


def coarse(d: dict, loc: np.ndarray, spread: np.ndarray) -> np.ndarray:
    """(N, cells): the per-place score (w - loc) / spread over judged places, averaged over COARSE x COARSE cells."""
    z = np.where(d["judged"], (d["w"].astype(np.float32) - loc) / spread, 0)
    n, h, w = z.shape
    return z.reshape(n, h // COARSE, COARSE, w // COARSE, COARSE).mean((2, 4)).reshape(n, -1)


def report(name: str, s: np.ndarray, y: np.ndarray, t: np.ndarray) -> None:
    c1 = caught_at_false_reject(y, s, 0.01)[0]
    dent = caught_at_false_reject(y[(y == 0) | (t == "dent")], s[(y == 0) | (t == "dent")], 0.01)[0]
    print(f"| {name} | {auroc(y, s):.3f} | {c1:.1%} | {dent:.0%} |")


def main() -> None:
    pf, pv = load("pf"), load("pv")
    loc, spread = pf["loc"], pf["spread"]
    good = pf["label"] == 0
    cal = pf["w"][good].astype(np.float32)
    w = pv["w"].astype(np.float32)
    y, t = pv["label"], pv["dtype"]
    twin = pv["index"][:, None] == pf["index"][good][None]  # the two sets are the same parts: never a part's twin
    (lc, pc), (lv, pp) = light_and_pose("line-pf-val", pf["index"][good]), light_and_pose("line-pv-val", pv["index"])
    lp = [np.concatenate([a / lc.std(), 3 * b / pc.std(0)], 1) for a, b in ((lc, pc), (lv, pp))]  # pose weighs 3x
    by = {"coarse window statistic": ((coarse(pv, loc, spread)[:, None] - coarse(pf, loc, spread)[good][None]) ** 2),
          "true stray-light vector": ((lv[:, None] - lc[None]) ** 2),
          "true stray-light vector and pose": ((lp[1][:, None] - lp[0][None]) ** 2)}
    print(f"screen: {int((y == 0).sum())} good, {int(y.sum())} defective parts of data/line-pv-val; "
          f"references: {len(cal)} good parts of data/line-pf-val\n")
    print("| reference | image AUROC | caught at 1 % | dents at 1 % |")
    print("|---|---|---|---|")
    report("all calibration good parts (the shipped spread)",
           (np.maximum((w - loc) / spread, 0) * pv["judged"]).reshape(len(w), -1).max(1), y, t)
    for what, d in by.items():
        order = np.argsort(np.where(twin, np.inf, d.sum(-1)), 1)
        for k in (10, 40):
            for q in (0.9, 1.0):
                s = np.array([(np.maximum((w[i] - np.maximum(np.quantile(cal[order[i, :k]], q, axis=0), loc))
                                          / spread, 0) * pv["judged"][i]).max() for i in range(len(w))])
                report(f"{what}: {k} nearest, {'max' if q == 1 else '90th percentile'}", s, y, t)


if __name__ == "__main__":
    main()
