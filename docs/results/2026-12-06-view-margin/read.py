"""The frame around the view (plan.md): the shipped file on each set, before (the warp replicates the view's border)
and with the frame around, on the same parts.

Usage: python read.py FILE SET:SPLIT ... (run from the repository's root). Prints per set and arm the good parts
rejected and by what (the window's score, the shape check's bend and the outline check's step, each over its own
threshold: above 1 rejects), the defective parts caught per kind, the parts with some of the view taken from outside
what the warp could read (``unseen_fraction > 0``), then the arms paired on the same parts."""

import sys

import numpy as np

from model.draem.adapt import image_scores
from model.draem.checkpoint import load_checkpoint
from model.draem.roi import AROUND_PX
from station.datasets import load_split


def main(argv: list[str]) -> None:
    file = argv[0]
    ck = load_checkpoint(file)
    cfg = ck.detector.config
    print(f"{file}: input {cfg.input_shape}, roi {cfg.roi}, threshold {ck.threshold:.4f}, around {AROUND_PX} px")
    for arg in argv[1:]:
        path, split = arg.split(":")
        sp = load_split(path, split, cfg.priors, cfg.input_shape, roi=cfg.roi, frame_aspect=cfg.frame_aspect,
                        dome_segments=cfg.dome_segments, around_px=AROUND_PX, progress=False)
        x = sp.priors.float()
        lab = sp.label.numpy() == 1
        kinds = np.array(sp.defect_type)
        got = {}
        for arm, around in (("before", None), ("around", sp.around.float())):
            s = image_scores(ck.detector, x, around=around)
            out = ck.detector.variation.zmaps(x, around=around)
            rej = s > ck.threshold
            got[arm] = rej
            bent = np.abs(out.edge_bend.numpy()) > 1
            per = ", ".join(f"{k} {int(rej[lab & (kinds == k)].sum())}/{int((lab & (kinds == k)).sum())}"
                            for k in sorted(set(kinds[lab])))
            print(f"\n{path}:{split} {arm}: {int(rej[~lab].sum())} of {int((~lab).sum())} good rejected "
                  f"({int((rej & bent & ~lab).sum())} bent beyond the shape check); {int(rej[lab].sum())} of "
                  f"{int(lab.sum())} defective caught ({100 * rej[lab].mean():.1f} %; {per}); parts partly outside "
                  f"what was read {int((out.unseen_fraction.numpy() > 0).sum())} of {len(lab)}", flush=True)
            for i in np.flatnonzero(rej & ~lab):
                print(f"  good part {int(sp.index[i])}: score {s[i]:.4f}, window {float(out.scores[i]):.3f}, bend "
                      f"{float(out.edge_bend[i]):.3f}, step {float(out.edge_step[i]):.3f}, unseen "
                      f"{float(out.unseen_fraction[i]):.4f}")
        d = got["around"].astype(float) - got["before"].astype(float)
        dd = d[lab]
        se = dd.std(ddof=1) / np.sqrt(len(dd)) if len(dd) > 1 else float("nan")
        print(f"{path} paired around - before: good rejected {int(d[~lab].sum()):+d}; defective caught "
              f"{100 * dd.mean():+.1f} pts (SE {100 * se:.1f}); parts whose decision differs: "
              f"{[int(sp.index[i]) for i in np.flatnonzero(d != 0)]}", flush=True)


if __name__ == "__main__":
    main(sys.argv[1:])
