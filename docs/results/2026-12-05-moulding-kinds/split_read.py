"""A reading of shape-screen-2b.json (after screen 2b, validation only): the bottom edge's sag beside the shipped
window with a budget of its own instead of the screens' larger-of rule. The window keeps its threshold at 1 % of B;
the sag's threshold is the largest sag z of A's good parts (none of A flagged by it). Prints what B, the five kinds and
seed 1199's warps give. Run from the repository's root."""

import json

import numpy as np

d = json.load(open("docs/results/2026-12-05-moulding-kinds/shape-screen-2b.json"))
centre, spread = d["sag_centre_px"], d["sag_spread_px"]
vz = np.abs(np.array(d["val_sags_px"]) - centre) / spread
wz = np.abs(np.array(d["warp_sags_px"]) - centre) / spread
vw, ww = np.array(d["val_log3"]), np.array(d["warp_log3"])
vl, vt, wl = np.array(d["val_labels"]), np.array(d["val_types"]), np.array(d["warp_labels"])
A, B = np.array(d["A"]), np.array(d["B_parts"])
t_window = float(np.percentile(vw[B], 99))
t_sag = float(vz[A].max())
for name, vflag, wflag in (("window alone", vw > t_window, ww > t_window),
                           ("window or sag", (vw > t_window) | (vz > t_sag), (ww > t_window) | (wz > t_sag))):
    kinds = {str(t): f"{(vflag[vt == t]).mean():.0%}" for t in sorted(set(vt) - {""})}
    print(f"{name}: B good rejected {vflag[B].sum()} of {len(B)}; five kinds caught {vflag[vl == 1].mean():.1%} "
          f"{kinds}; seed 1199: warps caught {wflag[wl == 1].mean():.1%}, good rejected {wflag[wl == 0].sum()} of "
          f"{(wl == 0).sum()}")
for shift, m in d["shifted_B"].items():
    sz, sw = np.abs(np.array(m["sags_px"]) - centre) / spread, np.array(m["log3"])
    print(f"B under {shift}: good rejected by the window {int((sw > t_window).sum())}, by the window or the sag "
          f"{int(((sw > t_window) | (sz > t_sag)).sum())} of {len(sw)}")
print(f"sag threshold: z {t_sag:.2f} (|sag - median| {t_sag * spread:.3f} input px)")
