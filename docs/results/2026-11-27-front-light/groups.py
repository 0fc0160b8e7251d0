"""Rules 31-32's criteria: image AUROC of groups of defects (by type and face), the shipped line P against another
line on the same parts (column Q: rule 31's front light, or rule 32's fringe panel), with a paired bootstrap SE
(the same parts under both lines, good and defective parts resampled by index). Faces from the ground-truth
normals as rule 25's faces.py reads them.
Usage: python groups.py EVAL_P DATA_P EVAL_Q DATA_Q OUT.json
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "2026-11-27-bright-field"))
from faces import auroc, faces_of  # rule 25's reader

GROUPS = {
    "front-face scratches and dents": lambda t, f: f == "front" and t in ("scratch", "dent"),
    "top-face scratches and dents": lambda t, f: f == "top" and t in ("scratch", "dent"),
    "top-face scratches": lambda t, f: f == "top" and t == "scratch",
    "front-face scratches": lambda t, f: f == "front" and t == "scratch",
    "front-face dents": lambda t, f: f == "front" and t == "dent",
    "top-face dents": lambda t, f: f == "top" and t == "dent",
    "all defects": lambda t, f: True,
}


def main() -> None:
    p_eval, p_data, q_eval, q_data, out = sys.argv[1:6]
    sp, gp = faces_of(p_eval, p_data)
    sq, gq = faces_of(q_eval, q_data)
    if set(sp) != set(sq) or gp != gq:
        raise SystemExit("the two evaluations scored different parts (or their defects differ)")
    good = np.array(sorted(set(sp) - set(gp)))
    rng = np.random.default_rng(0)
    rows = []
    print("| group | n | P | Q | Q - P (paired SE) | SEs |\n|---|---|---|---|---|---|")
    for name, member in GROUPS.items():
        bad = np.array(sorted(i for i, (t, f) in gp.items() if member(t, f)))
        if not len(bad):
            continue

        def gain(bi: np.ndarray, gi: np.ndarray) -> float:
            return (auroc(np.array([sq[i] for i in bi]), np.array([sq[i] for i in gi]))
                    - auroc(np.array([sp[i] for i in bi]), np.array([sp[i] for i in gi])))

        boot = [gain(rng.choice(bad, len(bad)), rng.choice(good, len(good))) for _ in range(1000)]
        p = auroc(np.array([sp[i] for i in bad]), np.array([sp[i] for i in good]))
        q = auroc(np.array([sq[i] for i in bad]), np.array([sq[i] for i in good]))
        se = float(np.std(boot))
        rows.append({"group": name, "n": len(bad), "P": p, "Q": q, "gain": q - p, "se": se})
        print(f"| {name} | {len(bad)} | {p:.3f} | {q:.3f} | {q - p:+.3f} ({se:.3f}) | {(q - p) / se:+.1f} |")
    Path(out).write_text(json.dumps(rows, indent=1))


if __name__ == "__main__":
    main()
