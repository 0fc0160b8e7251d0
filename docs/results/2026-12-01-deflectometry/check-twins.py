"""Plan 6's twin check: a line set's parts and their stripes' twins differ only in the light.

Usage: check-twins.py LINE_SET TWIN_SET [TWIN_SET ...]. Compares every 25th part's `params.json`, ignoring what the
stripes are expected to change (`scene.ring_fringe`, the count of saturated pixels, render timings) and what only
the line set records (visibility); prints each difference found and one summary line.
"""

import json
import sys
from pathlib import Path

EXPECTED = {"/scene/ring_fringe", "/n_saturated"}
EXPECTED_PREFIXES = ("/render_seconds", "/visibility", "/defect/snr")  # snr*: --visibility's records


def differences(a: object, b: object, path: str = "") -> list[str]:
    """Paths at which two parsed JSON values differ, outside the expected ones."""
    if path in EXPECTED or path.startswith(EXPECTED_PREFIXES):
        return []
    if isinstance(a, dict) and isinstance(b, dict):
        return [d for k in sorted(set(a) | set(b)) for d in differences(a.get(k), b.get(k), f"{path}/{k}")]
    return [] if a == b else [path]


def main(line: str, *twins: str) -> int:
    names = sorted(p.name for p in (Path(line) / "samples").iterdir())[::25]
    found = 0
    for twin in twins:
        for name in names:
            a = json.loads((Path(line) / "samples" / name / "params.json").read_text())
            b = json.loads((Path(twin) / "samples" / name / "params.json").read_text())
            for d in differences(a, b):
                print(f"{twin} {name}: {d}")
                found += 1
    print(f"{line}: {len(names)} parts x {len(twins)} twin sets, {found} unexpected differences")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:]))
