"""Development screen (sets read before; nothing is chosen on it): two files' cascade C (as shipped: above the
second look's gate, the larger of the window with its checks and the look network's finding) and the blend D of stop
119 (a quarter the window's, three quarters the network's finding, each over its own 1 % threshold, with the checks;
docs/results/2026-12-06-look-mean.md), each thresholded at 1 % of its own 370 good validation parts (data/line-pv-val)
and held fixed. Per part arrays from that study's arrays.py, for any file, cached in runs/ggx-900/arrays/.

Usage: python screen.py MODEL_A MODEL_B DATA:SPLIT ... (run from the repository's root with PYTHONPATH=.)."""

import sys
from pathlib import Path

import numpy as np

from model.draem.checkpoint import load_checkpoint
from model.draem.metrics import false_reject_threshold

sys.path.insert(0, "docs/results/2026-12-06-look-mean")
import arrays as look_mean_arrays  # stop 119's per-part arrays, for any file

CACHE = Path("runs/ggx-900/arrays")
WEIGHT = 0.25  # D's share of the window, as stop 119's plan chose it
VAL = "data/line-pv-val:val"


def arrays(model: str, arg: str) -> dict[str, np.ndarray]:
    """Label, kind, the decision score without the look (window units), the window's maximum (gate units) and the
    look network's finding on every part (window units), for one set's split."""
    path, split = arg.split(":")
    cache = CACHE / model.replace("/", "_") / f"{Path(path).name}_{split}.npz"
    if cache.exists():
        with np.load(cache) as d:
            return {k: d[k] for k in d.files}
    out = look_mean_arrays.arrays(path, split, model)
    cache.parent.mkdir(parents=True, exist_ok=True)
    np.savez(cache, **out)
    return out


class Decisions:
    """One file's C and D with their 1 % thresholds from its good validation parts."""

    def __init__(self, model: str):
        self.model, self.look = model, load_checkpoint(model).detector.variation.second_look
        v = arrays(model, VAL)
        good = ~v["label"]
        self.t_w = false_reject_threshold(v["score"][good], 0.01)
        self.t_f = false_reject_threshold(v["found"][good], 0.01)
        self.thresholds = {name: false_reject_threshold(f(v)[good], 0.01) for name, f in self.rules().items()}

    def rules(self):
        return {"C": self.cascade, "D": self.blend}

    def cascade(self, a: dict[str, np.ndarray]) -> np.ndarray:
        s = a["score"].copy()
        up = a["window_sd"] > float(self.look.calibration[0])
        s[up] = np.maximum(s[up], a["found"][up])
        return s

    def blend(self, a: dict[str, np.ndarray]) -> np.ndarray:
        checks = np.where(a["score"] > self.look.from_window_sd(a["window_sd"]) + 1e-4, a["score"], 0.0)
        return np.maximum(WEIGHT * a["score"] / self.t_w + (1 - WEIGHT) * a["found"] / self.t_f, checks / self.t_w)


def main(first: str, second: str, *sets: str) -> None:
    files = [Decisions(first), Decisions(second)]
    for f in files:
        print(f"{f.model}: C threshold {f.thresholds['C']:.4f}, D threshold {f.thresholds['D']:.4f}", flush=True)
    for arg in sets:
        print(f"\n{arg}")
        for f in files:
            a = arrays(f.model, arg)
            lab, kinds = a["label"], a["kind"]
            for name, rule in f.rules().items():
                rej = rule(a) > f.thresholds[name]
                per = ", ".join(f"{k} {int(rej[lab & (kinds == k)].sum())}/{int((lab & (kinds == k)).sum())}"
                                for k in sorted(set(kinds[lab])))
                print(f"  {f.model} {name}: good rejected {int(rej[~lab].sum())} of {int((~lab).sum())}; caught "
                      f"{int(rej[lab].sum())} of {int(lab.sum())} ({100 * rej[lab].mean():.1f} %; {per})", flush=True)


if __name__ == "__main__":
    main(*sys.argv[1:])
