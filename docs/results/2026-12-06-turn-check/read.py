"""plan.md's read: the shipped file on each fresh turned set as the station reads it (the frame around the view).

Usage: python read.py FILE SET:SPLIT ... (run from the repository's root). Prints per set the good parts rejected and
by what (the window's score, the shape check's bend and the outline check's step, each over its own threshold: above 1
rejects), the defective parts caught per kind, the parts with some of the view taken from outside what was read, the
parts' turns (``turn_deg``: median and range of the good parts', how many read none) and at which part, in the set's
order, the station's turn monitor and view monitor would first warn; writes read.json beside it (per set: those
counts and each part's turn, label and decision)."""

import json
import sys
from pathlib import Path

import numpy as np

from model.draem.adapt import image_scores
from model.draem.checkpoint import load_checkpoint
from station.datasets import load_split
from station.drift import TurnMonitor, ViewMonitor


def first_warning(monitor: TurnMonitor | ViewMonitor, values: np.ndarray) -> int | None:
    """The 1-based count of parts at which ``monitor`` first warns, fed ``values`` in order (NaN turns skipped, as
    the station skips a part whose model reads none); None if it never does."""
    for n, v in enumerate(values, 1):
        if np.isfinite(v) and monitor.update(float(v)) is not None:
            return n
    return None


def main(argv: list[str]) -> None:
    file = argv[0]
    ck = load_checkpoint(file)
    cfg = ck.detector.config
    print(f"{file}: input {cfg.input_shape}, roi {cfg.roi}, threshold {ck.threshold:.4f}, around {cfg.around_px} px, "
          f"turn centre {float(ck.detector.variation.turn_centre):+.2f} degrees")
    record = {}
    for arg in argv[1:]:
        path, split = arg.split(":")
        sp = load_split(path, split, cfg.priors, cfg.input_shape, roi=cfg.roi, frame_aspect=cfg.frame_aspect,
                        dome_segments=cfg.dome_segments, around_px=cfg.around_px, progress=False)
        x, around = sp.priors.float(), sp.around.float()
        lab = sp.label.numpy() == 1
        kinds = np.array(sp.defect_type)
        s = image_scores(ck.detector, x, around=around)
        out = ck.detector.variation.zmaps(x, around=around)
        rej = s > ck.threshold
        bent = np.abs(out.edge_bend.numpy()) > 1
        stepped = out.edge_step.numpy() > 1
        per = ", ".join(f"{k} {int(rej[lab & (kinds == k)].sum())}/{int((lab & (kinds == k)).sum())}"
                        for k in sorted(set(kinds[lab])))
        turn, unseen = out.turn_deg.numpy(), out.unseen_fraction.numpy()
        g = turn[~lab & np.isfinite(turn)]
        print(f"\n{path}:{split}: {int(rej[~lab].sum())} of {int((~lab).sum())} good rejected "
              f"({100 * rej[~lab].mean():.1f} %; {int((rej & bent & ~lab).sum())} bent beyond the shape check, "
              f"{int((rej & stepped & ~lab).sum())} stepped beyond the outline check); {int(rej[lab].sum())} of "
              f"{int(lab.sum())} defective caught ({100 * rej[lab].mean():.1f} %; {per}); parts partly outside "
              f"what was read {int((unseen > 0).sum())} of {len(lab)}", flush=True)
        print(f"  good parts' turn: median {np.median(g):+.2f}, {g.min():+.2f} to {g.max():+.2f} degrees; parts the "
              f"warp found no fit for {int(np.isnan(turn).sum())} of {len(turn)}; the turn monitor first warns at "
              f"part {first_warning(TurnMonitor(), turn)}, the view monitor at part "
              f"{first_warning(ViewMonitor(), unseen)}", flush=True)
        record[path] = {"good": int((~lab).sum()), "good_rejected": int(rej[~lab].sum()),
                        "defective": int(lab.sum()), "caught": int(rej[lab].sum()),
                        "outside": int((unseen > 0).sum()), "no_fit": int(np.isnan(turn).sum()),
                        "turn_deg": [None if np.isnan(t) else float(t) for t in turn],
                        "label": lab.astype(int).tolist(), "rejected": rej.astype(int).tolist()}
        for i in np.flatnonzero(rej & ~lab):
            print(f"  good part {int(sp.index[i])}: score {s[i]:.4f}, window {float(out.scores[i]):.3f}, bend "
                  f"{float(out.edge_bend[i]):.3f}, step {float(out.edge_step[i]):.3f}, unseen {unseen[i]:.4f}, turn "
                  f"{turn[i]:+.2f}")
    Path(__file__).with_name("read.json").write_text(json.dumps(record))


if __name__ == "__main__":
    main(sys.argv[1:])
