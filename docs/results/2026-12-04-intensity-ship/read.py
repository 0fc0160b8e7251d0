"""The plan's bars (plan.md): S (`PRIORS=intensity make model`) against the shipped file E63, on fresh seeds 1194 (held
out, the line as built) and 1195 (kinds nobody rendered), and what is reported beside them.

    PYTHONPATH=. .venv/bin/python docs/results/2026-12-04-intensity-ship/read.py > .../read.txt

Reads the reports copied into eval/ (run.sh's and make model's `station eval` folders). Each file at its stored
threshold: a part is rejected when its score is above it, or when the station would not judge its frame (eval.json's
`unjudged`), as `station eval` counts it. Writes read.json beside it.
"""
import csv
import json
from pathlib import Path

import numpy as np

from model.draem.metrics import auroc

HERE = Path(__file__).parent
TYPES = ("chip", "dent", "missing_stud", "scratch", "stain")
# E63's looks without each type, on its own report set (seed 1187): context, not paired
# (../2026-12-04-recipe-reproduction.md, "E63 (model/weights/README.md)")
E63_HELD_OUT_1187 = {"missing_stud": 1.000, "chip": 0.993, "stain": 0.955, "dent": 0.879, "scratch": 0.751}


def load(name: str, folder: Path | None = None) -> dict:
    """One report's parts in index order: labels, types, scores, and rejected at its stored threshold."""
    folder = folder or HERE / "eval" / name
    report = json.loads((folder / "eval.json").read_text())
    rows = sorted(csv.DictReader(open(folder / "scores.csv")), key=lambda r: int(r["index"]))
    index = np.array([int(r["index"]) for r in rows])
    score = np.array([float(r["score"]) for r in rows])
    left = np.array([str(i) in report.get("unjudged", {}) for i in index])
    return {"index": index, "label": np.array([int(r["label"]) for r in rows]),
            "type": np.array([r["defect_type"] for r in rows]), "score": score,
            "threshold": float(report["threshold"]), "rejected": (score > report["threshold"]) | left}


def type_auroc(d: dict, t: str) -> float:
    """Image AUROC of type ``t``'s defective parts against every good part."""
    keep = (d["label"] == 0) | (d["type"] == t)
    return auroc(d["label"][keep], d["score"][keep])


def paired_auroc_se(a: dict, b: dict, reps: int = 1000) -> float:
    """Bootstrap SE over parts of AUROC(a) - AUROC(b), the same parts resampled for both."""
    rng = np.random.default_rng(0)
    y, diffs = a["label"], []
    for _ in range(reps):
        i = rng.integers(0, len(y), len(y))
        if 0 < y[i].sum() < len(i):
            diffs.append(auroc(y[i], a["score"][i]) - auroc(y[i], b["score"][i]))
    return float(np.std(diffs))


def summary(d: dict) -> dict:
    y = d["label"]
    types = sorted({t for t in d["type"][y == 1]})
    return {"good": int((y == 0).sum()), "defective": int((y == 1).sum()), "threshold": d["threshold"],
            "good_rejected": int(d["rejected"][y == 0].sum()), "caught": float(d["rejected"][y == 1].mean()),
            "auroc": auroc(y, d["score"]),
            "by_type": {t: {"auroc": type_auroc(d, t), "caught": float(d["rejected"][d["type"] == t].mean()),
                            "parts": int((d["type"] == t).sum())} for t in types}}


def pair(s_name: str, e_name: str) -> dict:
    s, e = load(s_name), load(e_name)
    assert (s["index"] == e["index"]).all() and (s["label"] == e["label"]).all(), (s_name, e_name)
    return {"S": summary(s), "E63": summary(e), "auroc_diff_se": paired_auroc_se(s, e)}


def show(name: str, res: dict) -> None:
    print(name)
    for m in ("S", "E63"):
        r = res[m]
        print(f"  {m:4s} AUROC {r['auroc']:.4f}, {r['good_rejected']} of {r['good']} good rejected, "
              f"{100 * r['caught']:.1f} % of {r['defective']} caught (threshold {r['threshold']:.4f}); by type "
              + ", ".join(f"{t} {v['auroc']:.3f} / {100 * v['caught']:.0f} %" for t, v in r["by_type"].items()))
    print(f"  S - E63: AUROC {res['S']['auroc'] - res['E63']['auroc']:+.4f} (paired SE {res['auroc_diff_se']:.4f}), "
          f"caught {100 * (res['S']['caught'] - res['E63']['caught']):+.1f} points, good rejected "
          f"{res['S']['good_rejected'] - res['E63']['good_rejected']:+d}")


def main() -> None:
    out: dict = {"held_out_1194": pair("S-1194", "E63-1194"), "new_kinds_1195": pair("S-new-kinds-1195",
                                                                                       "E63-new-kinds-1195")}
    show("seed 1194, the line as built (held out)", out["held_out_1194"])
    show("seed 1195, kinds nobody rendered", out["new_kinds_1195"])
    h, k = out["held_out_1194"], out["new_kinds_1195"]
    bars = {
        "1 AUROC at least E63's - 0.02": h["S"]["auroc"] >= h["E63"]["auroc"] - 0.02,
        "2 caught at least E63's - 5 points, at most 2 more good rejected (1194)":
            h["S"]["caught"] >= h["E63"]["caught"] - 0.05
            and h["S"]["good_rejected"] <= h["E63"]["good_rejected"] + 2,
        "3 the same on kinds nobody rendered (1195)":
            k["S"]["caught"] >= k["E63"]["caught"] - 0.05
            and k["S"]["good_rejected"] <= k["E63"]["good_rejected"] + 2,
    }
    bench = HERE / "bench" / "pipeline.json"
    if bench.exists():
        rows = json.loads(bench.read_text())["rows"]
        out["bench"] = {r["checkpoint"]: {"p50_ms": r["p50_ms"], "p99_ms": r["p99_ms"]} for r in rows}
        shipped = out["bench"]["model/weights/default"]
        size_mb = sum(f.stat().st_size for f in (Path("model/weights/default.pt"), Path("model/weights/default.json")))
        bars["4 p99 <= 100 ms, file <= 30 MB"] = shipped["p99_ms"] <= 100 and size_mb / 1e6 <= 30
        print("bench: " + ", ".join(f"{c} p50 {v['p50_ms']:.1f} ms, p99 {v['p99_ms']:.1f} ms"
                                     for c, v in out["bench"].items()) + f"; shipped file {size_mb / 1e6:.1f} MB")
    out["bars"] = bars
    for name, ok in bars.items():
        print(f"bar {name}: {'holds' if ok else 'FAILS'}")
    held: dict = {}
    for t in TYPES:
        folder = HERE / "eval" / f"holdout-{t}-1194"
        if folder.exists():
            d = load(f"holdout-{t}-1194")
            held[t] = {"auroc": type_auroc(d, t), "caught": float(d["rejected"][d["type"] == t].mean()),
                       "good_rejected": int(d["rejected"][d["label"] == 0].sum()), "e63_1187": E63_HELD_OUT_1187[t]}
    out["held_out_types"] = held
    print("types left out of the look's training (seed 1194; E63's on seed 1187 for context): " + ", ".join(
        f"{t} {v['auroc']:.3f} ({100 * v['caught']:.0f} % caught; E63 {v['e63_1187']:.3f})" for t, v in held.items()))
    robust: dict = {}
    for look in ("built", "ggx", "rough"):
        folder = HERE / "eval" / f"S-{look}-1193"
        if folder.exists():
            s, r = load(f"S-{look}-1193"), load("", HERE.parent / "2026-12-04-intensity-robust" / "eval" / f"R-{look}")
            y = s["label"]
            robust[look] = {"S_good_rejected": int(s["rejected"][y == 0].sum()),
                            "R_good_rejected": int(r["rejected"][y == 0].sum()), "good": int((y == 0).sum()),
                            "S_caught": float(s["rejected"][y == 1].mean()),
                            "R_caught": float(r["rejected"][y == 1].mean()),
                            "score_correlation": float(np.corrcoef(s["score"], r["score"])[0, 1]),
                            "decisions_differ": int((s["rejected"] != r["rejected"]).sum())}
    out["seed_1193"] = robust
    for look, v in robust.items():
        print(f"seed 1193 {look}: S {v['S_good_rejected']} / R {v['R_good_rejected']} of {v['good']} good rejected, "
              f"caught S {100 * v['S_caught']:.1f} % / R {100 * v['R_caught']:.1f} %; scores correlate "
              f"{v['score_correlation']:.4f}, {v['decisions_differ']} decisions differ")
    (HERE / "read.json").write_text(json.dumps(out, indent=1) + "\n")


if __name__ == "__main__":
    main()
