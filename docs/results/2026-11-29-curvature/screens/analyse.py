import sys

import numpy as np

from model.draem import appearance_clusters as ac

for name in sys.argv[1:]:
    d = np.load(f"runs/s59/{name}.npz")
    c = d["coefs"]
    print(f"== {name}: coef std", np.round(c.std(0), 3))
    keys = ["ring", "light", "yaw", "alpha", "finish", "lx", "ly", "cx", "exposure"]
    print("corr(coef_k, param):")
    for k in keys:
        v = d[k]
        r = [np.corrcoef(c[:, j], v)[0, 1] if v.std() > 0 else 0 for j in range(c.shape[1])]
        # R^2 of param explained linearly by all coefs
        A = np.c_[c, np.ones(len(c))]
        res = v - A @ np.linalg.lstsq(A, v, rcond=None)[0]
        r2 = 1 - res.var() / max(v.var(), 1e-12)
        print(f"  {k:9s} R2(all)={r2:.2f} ", " ".join(f"{x:+.2f}" for x in r))
    centres, spread, labels = ac.group(c, 8)
    print("cluster sizes", np.bincount(labels))
    for k in keys:
        v = d[k]
        between = sum((labels == j).sum() * (v[labels == j].mean() - v.mean()) ** 2 for j in range(len(centres)))
        print(f"  eta2 {k:9s} {between / max(((v - v.mean()) ** 2).sum(), 1e-12):.2f}")
