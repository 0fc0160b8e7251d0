"""`station adapt` with the frame around the view (plan.md): the shipped file, and the shipped file adapted on the same
200 good parts of a turned line reading the view alone (as until now) and with the frame around.

Usage: python read.py [SET] (run from the repository's root; SET defaults to plan.md's data/adapt-1212-turned5, split
test). Good parts in index order: those at even places adapt (the first 200; `station adapt`'s defaults:
cross-fitted, 1 %, floor on), those at odd places and every defective part are judged, each file reading what it
reads (the shipped and around files the frame around, the view file the view alone). Prints what each adaptation
said (its refitted checks), the table, defective parts caught per kind, each judged good part a file rejects with
what rejected it (the window's score, the shape check's bend and the outline check's step, each in units of its own
threshold: above 1 rejects) and the parts partly outside what was read."""

import sys

import numpy as np
import torch

from model.draem.adapt import AdaptConfig, adapt, image_scores
from model.draem.checkpoint import load_checkpoint
from station.evaluation import model_split

MODEL, DATA, ADAPT_ON = "model/weights/default", "data/adapt-1212-turned5", 200


def main(argv: list[str]) -> None:
    data = argv[0] if argv else DATA
    ck = load_checkpoint(MODEL)
    sp = model_split(ck, MODEL, data, "test")
    x, around = sp.priors.float(), sp.around.float()
    label = sp.label.numpy() == 1
    good = np.flatnonzero(~label)
    fit, judged_good = torch.from_numpy(good[0::2][:ADAPT_ON]), good[1::2]
    judged = np.concatenate([judged_good, np.flatnonzero(label)])
    lab = label[judged]
    kinds = np.array([sp.defect_type[i] for i in judged])
    names = sorted(set(kinds[lab]))
    rows = [("shipped", ck.detector, ck.threshold, True)]
    for arm, with_around in (("view", False), ("around", True)):
        det, res = adapt(ck.detector, x[fit], sp.object_mask[fit], AdaptConfig(), progress=False,
                         around=around[fit] if with_around else None)
        print(f"{arm}: adapted on {len(fit)}, around_px {det.config.around_px}, threshold "
              f"{res.threshold.threshold:.4f}; {res.shape}", flush=True)
        rows.append((arm, det, res.threshold.threshold, with_around))
    print(f"\njudged: {len(judged_good)} good parts (none adapted on), {int(lab.sum())} defective "
          f"({', '.join(f'{k} {int((kinds[lab] == k).sum())}' for k in names)})")
    print("| file | threshold | good parts rejected | defective caught | " + " | ".join(names) + " |\n|---|---|---|---|"
          + "---|" * len(names))
    xj, aj = x[torch.from_numpy(judged)], around[torch.from_numpy(judged)]
    results = []
    for name, det, thr, with_around in rows:
        a = aj if with_around else None
        s = image_scores(det, xj, around=a)
        rej = s > thr
        per = " | ".join(f"{int(rej[lab & (kinds == k)].sum())}/{int((lab & (kinds == k)).sum())}" for k in names)
        print(f"| {name} | {thr:.4f} | {int(rej[~lab].sum())} of {int((~lab).sum())} | {int(rej[lab].sum())} of "
              f"{int(lab.sum())} ({100 * rej[lab].mean():.1f} %) | {per} |", flush=True)
        results.append((name, det, thr, a, s, rej))
    print()
    for name, det, thr, a, s, rej in results:
        out = det.variation.zmaps(xj, around=a)
        print(f"{name}: parts partly outside what was read {int((out.unseen_fraction.numpy() > 0).sum())} of "
              f"{len(judged)}")
        for i in np.flatnonzero(rej & ~lab):
            print(f"  good part {int(sp.index[judged[i]])}: score {s[i]:.4f} > {thr:.4f}; window "
                  f"{float(out.scores[i]):.3f}, bend {float(out.edge_bend[i]):.3f}, step {float(out.edge_step[i]):.3f}"
                  f", unseen {float(out.unseen_fraction[i]):.4f}")
    d = results[2][5].astype(float) - results[1][5].astype(float)
    dd = d[lab]
    print(f"\npaired around - view: good rejected {int(d[~lab].sum()):+d}; defective caught {100 * dd.mean():+.1f} pts "
          f"(SE {100 * dd.std(ddof=1) / np.sqrt(len(dd)):.1f}); parts whose decision differs: "
          f"{[int(sp.index[judged[i]]) for i in np.flatnonzero(d != 0)]}")


if __name__ == "__main__":
    main(sys.argv[1:])
