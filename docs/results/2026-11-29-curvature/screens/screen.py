"""Stop 59 screen: refit the variation model (station variation --refit) with the clusters changed.
mode ring: k-means on the coefficients with the panel (ring) brightness direction taken out (an oracle: the
direction is the least-squares fit of the rendered ring radiance on the coefficients, in spread units; at run time
the distance along it is the same to every centre, so the weights are unchanged by it). mode kN: N clusters, one per
20 parts allowed."""
import sys

import numpy as np

from model.draem import appearance_clusters as ac
from station.evaluation import fit_variation

mode, model, data, val, out = sys.argv[1:6]
clusters = None
if mode == "ring":
    d = np.load("runs/s59/X0.npz")
    ring, ref = d["ring"], d["coefs"]
    original = ac.group

    def group(coefs, clusters):
        assert coefs.shape == ref.shape and np.allclose(coefs, ref, rtol=1e-3, atol=1e-2), "parts out of order"
        m = min(clusters, len(coefs) // ac.CLUSTER_PARTS)
        spread = ac.spread_of(coefs)
        points = coefs / spread
        a = np.c_[points, np.ones(len(points))]
        beta = np.linalg.lstsq(a, ring, rcond=None)[0][:-1]
        u = beta / np.linalg.norm(beta)
        print("ring direction (spread units):", np.round(u, 2), flush=True)
        points = points - np.outer(points @ u, u)
        centres, labels = ac.kmeans(points, m)
        while len(centres) > 1:
            counts = np.bincount(labels, minlength=len(centres))
            if counts.min() >= ac.MIN_CLUSTER_PARTS:
                break
            centres = np.delete(centres, counts.argmin(), 0)
            labels = ac.nearest(centres, points)
            centres = np.stack([points[labels == j].mean(0) if (labels == j).any() else centres[j]
                                for j in range(len(centres))])
            labels = ac.nearest(centres, points)
        width = max(float(np.median(np.sqrt(ac.sq_distances(points, centres).min(1)))), ac.SPREAD_FLOOR)
        print("sizes", np.bincount(labels), flush=True)
        return (centres / width).astype(np.float32), (spread * width).astype(np.float32), labels

    ac.group = group
elif mode.startswith("k"):
    clusters = int(mode[1:])
    ac.CLUSTER_PARTS = 20
print(fit_variation(model, data, out, val_data=val, decision="variation", refit=True, clusters=clusters))
