"""Channel screen on the validation set (cw-pv.npz from chan_windows.py; stdout: screen.txt):
 per-place location/spread from the odd good parts, scored on the even good
parts and every defective part. Rows: the shipped statistic (max over channels, then one place statistic), each
channel alone, per-channel place statistics maxed, polarization channels only."""
import sys

import cv2
import numpy as np

from model.draem.metrics import auroc
from model.draem.variation import WINDOW_BLUR_PX, WINDOW_QUANTILE

d = np.load(sys.argv[1])
w, judged, label, dtype = d["w"].astype(np.float32), d["judged"], d["label"], d["dtype"]
w = w * judged[:, None]
good = np.flatnonzero(label == 0)
cal, ev_good = good[1::2], good[0::2]
bad = np.flatnonzero(label == 1)
region = judged.any(0)


def place(ws):  # (N, H, W) -> location, spread as the model fits them (floor: 5th pct of spread over region)
    loc = np.median(ws, 0)
    spread = cv2.GaussianBlur(np.percentile(ws, WINDOW_QUANTILE, 0) - loc, (0, 0), WINDOW_BLUR_PX)
    return loc, np.maximum(spread, max(float(np.percentile(spread[region], 5)), 1e-3))


def scores(stat):  # (N, H, W) statistic -> image scores with place stats from cal
    loc, spread = place(stat[cal])
    return (np.maximum((stat - loc) / spread, 0) * judged).reshape(len(stat), -1).max(1)


def per_channel(chans):
    return np.max([scores(w[:, c]) for c in chans], 0)


def report(name, s):
    g, b = s[ev_good], s[bad]
    y = np.r_[np.zeros(len(g)), np.ones(len(b))]
    a = auroc(y, np.r_[g, b])
    t1, t5 = np.quantile(g, 0.99, method="higher"), np.quantile(g, 0.95, method="higher")
    per = []
    for t in sorted(set(dtype[bad])):
        sb = s[bad][dtype[bad] == t]
        a_t = auroc(np.r_[np.zeros(len(g)), np.ones(len(sb))], np.r_[g, sb])
        per.append(f"{t[:5]} {a_t:.3f}/{(sb > t1).mean():.0%}")
    per = " ".join(per)
    print(f"{name:34s} AUROC {a:.3f} caught@1% {(b > t1).mean():.1%} @5% {(b > t5).mean():.1%} | {per}")


C = w.shape[1]
report("shipped: max over channels", scores(w.max(1)))
for c in range(C):
    report(f"channel {c} alone", scores(w[:, c]))
report("per-channel place, max", per_channel(range(C)))
report("polarization only (1,2), max", per_channel([1, 2]))
report("pol only, max-then-place", scores(w[:, 1:].max(1)))
print("good:", len(ev_good), "cal:", len(cal), "bad:", len(bad))


def placed(c):
    loc, spread = place(w[cal, c])
    return np.maximum((w[:, c] - loc) / spread, 0) * judged


P = np.stack([placed(c) for c in range(C)], 1)  # (N, C, H, W) per-channel place-normalised
report("sum of placed channels", P.sum(1).reshape(len(P), -1).max(1))
report("rss of placed channels", np.sqrt((P ** 2).sum(1)).reshape(len(P), -1).max(1))
report("sum of raw channels, then place", scores(w.sum(1)))
report("rss of raw channels, then place", scores(np.sqrt((w ** 2).sum(1))))
