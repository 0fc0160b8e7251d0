"""Two files on the same held-out parts, each at its own threshold (plan.md): good parts rejected, defective parts
caught per kind, and the paired difference (second minus first).

Usage: python paired.py FIRST SECOND SET (checkpoints without suffix; SET's test split; run from the repository's
root)."""

import sys

import numpy as np

from model.draem.adapt import image_scores
from model.draem.checkpoint import load_checkpoint
from station.evaluation import model_split


def main(first: str, second: str, data: str) -> None:
    got = []
    for path in (first, second):
        ck = load_checkpoint(path)
        sp = model_split(ck, path, data, "test")
        lab = sp.label.numpy() == 1
        kinds = np.array(sp.defect_type)
        s = image_scores(ck.detector, sp.priors.float(), around=None if sp.around is None else sp.around.float())
        rej = s > ck.threshold
        per = ", ".join(f"{k} {int(rej[lab & (kinds == k)].sum())}/{int((lab & (kinds == k)).sum())}"
                        for k in sorted(set(kinds[lab])))
        fit = ck.meta.get("train", {}).get("variation", {}).get("fit_parts")
        print(f"{path} (fit on {fit} good parts, threshold {ck.threshold:.4f}): {int(rej[~lab].sum())} of "
              f"{int((~lab).sum())} good rejected; {int(rej[lab].sum())} of {int(lab.sum())} defective caught "
              f"({100 * rej[lab].mean():.1f} %; {per})", flush=True)
        got.append((sp.index, lab, rej))
    assert got[0][0] == got[1][0]
    lab = got[0][1]
    d = got[1][2].astype(float) - got[0][2].astype(float)
    dd = d[lab]
    print(f"paired second - first: good rejected {int(d[~lab].sum()):+d}; defective caught {100 * dd.mean():+.1f} pts "
          f"(SE {100 * dd.std(ddof=1) / np.sqrt(len(dd)):.1f}); parts whose decision differs: "
          f"{[int(got[0][0][i]) for i in np.flatnonzero(d != 0)]}")


if __name__ == "__main__":
    main(*sys.argv[1:])
