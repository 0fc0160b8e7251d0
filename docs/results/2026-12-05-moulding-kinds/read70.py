"""rule-70-plan.md's reading: C (the shipped file with the shape check) against the shipped file on the same parts,
set by set: good parts rejected, defective parts caught (per type on seed 1198), paired. Run by rule70.sh."""

import csv
import json
from pathlib import Path

HERE = Path(__file__).parent
RESULTS = HERE.parent
SETS = {  # tag: (C's report, the shipped file's report of the same parts)
    "1198": ("rule70/C-1198", HERE / "eval/line"),
    "1194": ("rule70/C-1194", RESULTS / "2026-12-04-intensity-ship/eval/S-1194"),
    "ggx": ("rule70/C-ggx", RESULTS / "2026-12-04-intensity-robust/eval/R-ggx"),
    "rough": ("rule70/C-rough", RESULTS / "2026-12-04-intensity-robust/eval/R-rough"),
    "chamfer03": ("rule70/C-chamfer03", RESULTS / "2026-12-04-ship-otherwise/eval/S-chamfer03"),
    "round03": ("rule70/C-round03", RESULTS / "2026-12-04-ship-otherwise/eval/S-round03"),
}


def decisions(report: Path) -> dict[str, tuple[str, str, bool]]:
    threshold = json.loads((report / "eval.json").read_text())["threshold"]
    return {r["index"]: (r["label"], r["defect_type"], float(r["score"]) > threshold)
            for r in csv.DictReader(open(report / "scores.csv"))}


def main() -> None:
    out = {}
    for tag, (c, base) in SETS.items():
        dc, db = decisions(HERE / c), decisions(Path(base))
        assert dc.keys() == db.keys() and all(dc[k][:2] == db[k][:2] for k in dc), tag
        groups = {"good rejected": [k for k in dc if dc[k][0] == "0"],
                  "defective caught": [k for k in dc if dc[k][0] == "1"]}
        for t in sorted({v[1] for v in dc.values()} - {""}):
            groups[f"{t} caught"] = [k for k in dc if dc[k][1] == t]
        row = {name: {"parts": len(ks), "C": sum(dc[k][2] for k in ks), "shipped": sum(db[k][2] for k in ks),
                      "C only": sum(dc[k][2] and not db[k][2] for k in ks),
                      "shipped only": sum(db[k][2] and not dc[k][2] for k in ks)} for name, ks in groups.items()}
        out[tag] = row
        for name, r in row.items():
            print(f"{tag:10s} {name:22s} of {r['parts']:4d}: C {r['C']:4d}, shipped {r['shipped']:4d} "
                  f"(C only {r['C only']}, shipped only {r['shipped only']})")
    (HERE / "rule70" / "read.json").write_text(json.dumps(out, indent=1))


if __name__ == "__main__":
    main()
