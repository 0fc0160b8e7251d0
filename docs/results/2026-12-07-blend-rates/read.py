"""plan.md's read: the shipped file's cascade C against its blend D on one fresh set: at matched rates of good parts
rejected (threshold from the set's good parts; ../2026-12-07-matched-rates/curves.py's table) with a bootstrap SE of
D - C, and each at its own 1 % threshold from the good validation parts (../2026-12-07-ggx-train/screen.py's
Decisions).

Usage: python read.py SET (SET's test split; run from the repository's root with PYTHONPATH=.)."""

import sys

sys.path[:0] = ["docs/results/2026-12-07-ggx-train", "docs/results/2026-12-07-matched-rates"]
from curves import matched  # noqa: E402
from screen import Decisions, arrays  # noqa: E402

MODEL = "model/weights/default"


def main(data: str) -> None:
    f = Decisions(MODEL)
    a = arrays(MODEL, f"{data}:test")
    lab = a["label"]
    c, d = f.cascade(a), f.blend(a)
    print(f"== {data}: {int((~lab).sum())} good, {int(lab.sum())} defective parts")
    for name, s in (("C", c), ("D", d)):
        rej = s > f.thresholds[name]
        print(f"{name} at its own threshold {f.thresholds[name]:.4f}: {int(rej[~lab].sum())} of {int((~lab).sum())} "
              f"good rejected ({100 * rej[~lab].mean():.2f} %), {int(rej[lab].sum())} of {int(lab.sum())} defective "
              f"caught ({100 * rej[lab].mean():.1f} %)")
    matched(c, d, lab, ("C", "D"))


if __name__ == "__main__":
    main(sys.argv[1])
