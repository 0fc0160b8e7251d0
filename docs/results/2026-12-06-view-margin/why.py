"""Read after T (plan.md), to explain, nothing chosen on it: the parts whose decision differs on a set, each arm's
station score, window score (the variation model's 1 % point is its threshold's scale), shape check bend, outline
check step and unseen share.

Usage: python why.py FILE SET:SPLIT INDEX ... (run from the repository's root)."""

import sys

from model.draem.adapt import image_scores
from model.draem.checkpoint import load_checkpoint
from model.draem.roi import AROUND_PX
from station.datasets import load_split, subset


def main(argv: list[str]) -> None:
    ck = load_checkpoint(argv[0])
    cfg = ck.detector.config
    path, split = argv[1].split(":")
    wanted = [int(i) for i in argv[2:]]
    sp = load_split(path, split, cfg.priors, cfg.input_shape, limit=max(wanted) + 1, roi=cfg.roi,
                    frame_aspect=cfg.frame_aspect, dome_segments=cfg.dome_segments, around_px=AROUND_PX,
                    progress=False)
    sp = subset(sp, [sp.index.index(i) for i in wanted])
    x = sp.priors.float()
    for arm, around in (("before", None), ("around", sp.around.float())):
        s = image_scores(ck.detector, x, around=around)
        out = ck.detector.variation.zmaps(x, around=around)
        for j, i in enumerate(wanted):
            said = "rejected" if s[j] > ck.threshold else "passed"
            print(f"part {i} ({sp.defect_type[j] or 'good'}) {arm}: score {s[j]:.4f} ({said}), "
                  f"window {float(out.scores[j]):.3f}, bend {float(out.edge_bend[j]):.3f}, step "
                  f"{float(out.edge_step[j]):.3f}, unseen {float(out.unseen_fraction[j]):.4f}", flush=True)


if __name__ == "__main__":
    main(sys.argv[1:])
