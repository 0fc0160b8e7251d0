"""Rules 3 and 4 (rule.md): candidates' image scores against the shipped statistic's on one labelled set, with paired
bootstrap SEs (1000 resamples of good and defective parts, thresholds re-estimated in each) of caught at 1 % and 5 %,
image AUROC and each type's image AUROC."""

from __future__ import annotations

import numpy as np
from sklearn.metrics import roc_auc_score

from model.draem.metrics import detection_by_type, false_reject_threshold

TYPES = ("chip", "dent", "missing_stud", "scratch", "stain")


def caught(lab: np.ndarray, s: np.ndarray, rate: float) -> float:
    t = false_reject_threshold(s[lab == 0], rate)
    return float((s[lab == 1] > t).mean())


def compare(
    lab: np.ndarray, typ: np.ndarray, cands: dict[str, np.ndarray], base: str = "shipped", resamples: int = 1000
) -> dict[str, dict]:
    """{candidate: figures, gains over ``base`` with SEs and, for the others, which of rule 3's (a)-(d) pass}."""
    rng = np.random.default_rng(0)
    gi, di = np.where(lab == 0)[0], np.where(lab == 1)[0]
    keys = ("c1", "c5", "auc", *TYPES)
    boots = {k: {m: [] for m in keys} for k in cands}
    for _ in range(resamples):
        i = np.concatenate([rng.choice(gi, len(gi)), rng.choice(di, len(di))])
        for k, s in cands.items():
            boots[k]["c1"].append(caught(lab[i], s[i], 0.01))
            boots[k]["c5"].append(caught(lab[i], s[i], 0.05))
            boots[k]["auc"].append(roc_auc_score(lab[i], s[i]))
            for t in TYPES:
                sel = (lab[i] == 0) | (typ[i] == t)
                boots[k][t].append(roc_auc_score(lab[i][sel], s[i][sel]))
    out: dict[str, dict] = {}
    for k in [base, *[k for k in cands if k != base]]:
        s = cands[k]
        rep = detection_by_type(lab, s, typ, validation=(lab, s))
        r = {"auroc": rep.overall.image_auroc, "c1": rep.overall.caught[0.01], "c5": rep.overall.caught[0.05]}
        r.update({t: rep.per_type[t].image_auroc for t in TYPES})
        r.update({t + "_c1": rep.per_type[t].caught[0.01] for t in TYPES})
        for m in keys:
            d = np.array(boots[k][m]) - np.array(boots[base][m])
            r[f"d_{m}"], r[f"se_{m}"] = float(d.mean()), float(d.std())
        if k != base:
            r["passes"] = {
                "a": r["d_c1"] > r["se_c1"],
                "b": r["c5"] >= out[base]["c5"],
                "c": r["d_auc"] > -r["se_auc"],
                "d": all(r[f"d_{t}"] > -r[f"se_{t}"] for t in TYPES),
            }
        out[k] = r
        print(
            f"{k:10s} AUROC {r['auroc']:.3f} (d {r['d_auc']:+.3f} se {r['se_auc']:.3f}) @1% {r['c1']:.0%} "
            f"(d {r['d_c1']:+.3f} se {r['se_c1']:.3f}) @5% {r['c5']:.0%} "
            + " ".join(f"{t[:5]} {r[t]:.3f} ({r[f'd_{t}']:+.3f}/{r[f'se_{t}']:.3f}) {r[t + '_c1']:.0%}" for t in TYPES)
            + (f" passes {r['passes']}" if "passes" in r else ""),
            flush=True,
        )
    return out


def held_out(
    lab: np.ndarray,
    typ: np.ndarray,
    cands: dict[str, np.ndarray],
    val_lab: np.ndarray,
    val_cands: dict[str, np.ndarray],
    name: str,
) -> dict[str, dict]:
    """Each candidate on a held-out set with its validation thresholds held fixed (no SEs: nothing is chosen here)."""
    out = {}
    for k, s in cands.items():
        rep = detection_by_type(lab, s, typ, validation=(val_lab, val_cands[k]))
        r = {
            "auroc": rep.overall.image_auroc,
            "c1": rep.overall.caught[0.01],
            "c5": rep.overall.caught[0.05],
            "good_rejected_1": rep.false_reject_observed[0.01],
            "good_rejected_5": rep.false_reject_observed[0.05],
        }
        r.update({t: rep.per_type[t].image_auroc for t in TYPES})
        r.update({t + "_c1": rep.per_type[t].caught[0.01] for t in TYPES})
        out[k] = r
        print(
            f"{name} {k:10s} AUROC {r['auroc']:.3f} @1% {r['c1']:.0%} ({r['good_rejected_1']:.1%}) @5% "
            f"{r['c5']:.0%} " + " ".join(f"{t[:5]} {r[t]:.3f} {r[t + '_c1']:.0%}" for t in TYPES),
            flush=True,
        )
    return out
