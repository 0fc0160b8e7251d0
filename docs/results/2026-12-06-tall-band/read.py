"""The tall band's readings (plan.md, plan-2.md): each arm's file on each set, as the station judges it.

Usage: python read.py B_FILE T_FILE SET:SPLIT ... (run from the repository's root). Prints per set and arm the good
parts rejected and by what (the window's score, the shape check's bend and the outline check's step, each over its
own threshold: above 1 rejects; a score above all three came from the look network), the defective parts caught at
the file's threshold per kind, and the share of parts with some input pixel taken from outside the frame
(``unseen_fraction > 0``); then, per set, T against B on the same parts: the paired difference in defective parts
caught (points, with its standard error) and in good parts rejected (added for plan 2: read.txt predates it)."""

import os
import sys
from typing import NamedTuple

import numpy as np

from model.draem.adapt import image_scores
from model.draem.checkpoint import Checkpoint, load_checkpoint
from model.draem.variation import VariationOutput
from station.evaluation import model_split


class Scored(NamedTuple):
    """One file's judgement of one set's split, per part: the station's score (``rejected`` above the file's
    threshold), the variation model's output (its window scores and frame checks), defective or not, and the kind."""

    score: np.ndarray
    rejected: np.ndarray
    out: VariationOutput
    defective: np.ndarray
    kinds: np.ndarray


def scored(ck: Checkpoint, file: str, path: str, split: str) -> Scored:
    """Score every part of ``path``'s ``split`` with ``ck`` (loaded from ``file``), as the station judges it."""
    sp = model_split(ck, file, path, split)
    x = sp.priors.float()
    lab = sp.label.numpy() == 1
    s = image_scores(ck.detector, x)
    return Scored(s, s > ck.threshold, ck.detector.variation.zmaps(x), lab,
                  np.array([sp.defect_type[i] or "" for i in range(len(lab))]))


def judge(arm: str, ck: Checkpoint, file: str, path: str, split: str) -> tuple[np.ndarray, np.ndarray]:
    """Print one arm's reading of one set; return (rejected, defective) per part."""
    s, rej, out, lab, kinds = scored(ck, file, path, split)
    names = sorted(set(kinds[lab]))
    unseen = out.unseen_fraction.numpy() > 0
    per = ", ".join(f"{k} {int(rej[lab & (kinds == k)].sum())}/{int((lab & (kinds == k)).sum())}" for k in names)
    caught = f"{int(rej[lab].sum())} of {int(lab.sum())} defective caught ({100 * rej[lab].mean():.1f} %; {per})" \
        if lab.any() else "no defective parts"
    print(f"\n{path}:{split} {arm}: {int(rej[~lab].sum())} of {int((~lab).sum())} good rejected; {caught}; "
          f"parts partly outside the view {int(unseen.sum())} of {len(lab)}", flush=True)
    for i in np.flatnonzero(rej & ~lab):
        print(f"  good part {int(i)}: score {s[i]:.4f}, window {float(out.scores[i]):.3f}, bend "
              f"{float(out.edge_bend[i]):.3f}, step {float(out.edge_step[i]):.3f}, unseen "
              f"{float(out.unseen_fraction[i]):.4f}")
    return rej, lab


def paired(path: str, b: tuple[np.ndarray, np.ndarray], t: tuple[np.ndarray, np.ndarray]) -> None:
    """Print T against B on the same parts: defective caught (points, SE of the paired mean) and good rejected."""
    (rb, lab), (rt, _) = b, t
    line = f"{path} paired T - B: good rejected {int(rt[~lab].sum()) - int(rb[~lab].sum()):+d}"
    if lab.any():
        d = rt[lab].astype(float) - rb[lab].astype(float)
        se = d.std(ddof=1) / np.sqrt(len(d)) if len(d) > 1 else float("nan")
        line += (f"; defective caught {100 * d.mean():+.1f} pts (SE {100 * se:.1f}; T only {int((d > 0).sum())}, "
                 f"B only {int((d < 0).sum())})")
    print(line, flush=True)


def main(argv: list[str]) -> None:
    files = {"B": argv[0], "T": argv[1]}
    cks = {arm: load_checkpoint(path) for arm, path in files.items()}
    for arm, path in files.items():
        print(f"{arm}: {path}, input {cks[arm].detector.config.input_shape}, threshold {cks[arm].threshold:.4f}, "
              f"{os.path.getsize(path + '.pt') / 1e6:.1f} MB")
    for arg in argv[2:]:
        path, split = arg.split(":")
        got = {arm: judge(arm, ck, files[arm], path, split) for arm, ck in cks.items()}
        paired(path, got["B"], got["T"])


if __name__ == "__main__":
    main(sys.argv[1:])
