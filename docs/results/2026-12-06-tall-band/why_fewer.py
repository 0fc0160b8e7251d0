"""Plan 2's square set read again for the parts the two files judge differently (written after the reading, to
explain it; nothing is chosen on it). Usage: python why_fewer.py B_FILE T_FILE SET:SPLIT. For each part one file
rejects and the other passes: its kind, and per file the score over the file's threshold and the window's score
(a score above the window's mapping came from the look network); then the median window score of the good parts
and of the defective ones per file."""

import sys

import numpy as np
from read import scored  # beside this script

from model.draem.checkpoint import load_checkpoint

files = {"B": sys.argv[1], "T": sys.argv[2]}
path, split = sys.argv[3].split(":")
got = {}
for arm, file in files.items():
    ck = load_checkpoint(file)
    r = scored(ck, file, path, split)
    w, lab = r.out.scores.numpy(), r.defective
    got[arm] = (r.score / ck.threshold, w)
    print(f"{arm}: window median good {np.median(w[~lab]):.3f}, defective {np.median(w[lab]):.3f}", flush=True)
(rb, wb), (rt, wt) = got["B"], got["T"]
for i in np.flatnonzero((rb > 1) != (rt > 1)):
    print(f"part {int(i)} ({r.kinds[i] or 'good'}): B score/threshold {rb[i]:.4f} window {wb[i]:.3f}; "
          f"T {rt[i]:.4f} window {wt[i]:.3f}")
