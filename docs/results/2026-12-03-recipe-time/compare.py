"""The refit's variation model against the shipped file's, buffer by buffer: the largest difference relative to
the shipped buffer's largest magnitude (appearance components up to sign, as the fit defines them, and the cluster
centres, their coordinates, with them). Prints a table and writes compare.json beside this script.
Usage: compare.py REFIT [SHIPPED]."""

from __future__ import annotations

import json
import sys
from pathlib import Path

import torch

from model.draem.checkpoint import load_checkpoint


def variation_state(path: str) -> dict[str, torch.Tensor]:
    sd = load_checkpoint(path).detector.state_dict()
    return {k: v for k, v in sd.items() if k.startswith("variation.")}


def component_signs(a: dict[str, torch.Tensor], b: dict[str, torch.Tensor]) -> torch.Tensor:
    """+1 or -1 per appearance component: the sign that turns the refit's component into the shipped one's."""
    flat_a, flat_b = a["variation.components"].double().flatten(1), b["variation.components"].double().flatten(1)
    return torch.where((flat_a * flat_b).sum(1) < 0, -1.0, 1.0).double()


def relative(a: torch.Tensor, b: torch.Tensor, name: str, sign: torch.Tensor) -> float:
    a, b = a.double(), b.double()
    if name.endswith(".components"):  # each component up to sign
        a = (a.flatten(1) * sign[:, None]).view_as(b)
    elif name.endswith(".cluster_centres"):  # coordinates along the components: they flip with them
        a = a * sign
    scale = float(b.abs().max()) or 1.0
    return float((a - b).abs().max()) / scale


def main() -> None:
    refit, shipped = sys.argv[1], sys.argv[2] if len(sys.argv) > 2 else "model/weights/default"
    a, b = variation_state(refit), variation_state(shipped)
    sign = component_signs(a, b)
    rows = []
    for k in b:
        if k not in a or a[k].shape != b[k].shape:
            rows.append({"buffer": k, "shape": list(b[k].shape), "relative": None,
                         "note": f"refit shape {list(a[k].shape) if k in a else 'absent'}"})
            continue
        rows.append({"buffer": k, "shape": list(b[k].shape), "relative": relative(a[k], b[k], k, sign)})
    for r in rows:
        rel = "n/a" if r["relative"] is None else f"{r['relative']:.2e}"
        print(f"{r['buffer']:<40} {r['shape']!s:<22} {rel:>10} {r.get('note', '')}")
    report = {"refit": refit, "shipped": shipped, "signs": sign.tolist(), "rows": rows}
    (Path(__file__).parent / "compare.json").write_text(json.dumps(report, indent=1))


if __name__ == "__main__":
    main()
