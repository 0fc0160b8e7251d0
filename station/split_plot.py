"""The picture of ``station split``: each validation part's two scores, one point per part, with the split's two
thresholds. A part right of the first camera's line or above the second camera's is rejected; the good parts there
are the budget, the defective parts left in the lower left corner are what the two cameras miss together."""

from __future__ import annotations

from pathlib import Path

EDGE = 1e-6  # scores are clipped into [EDGE, 1 - EDGE] for the logit axes


def plot_split(report: dict, path: str | Path) -> None:
    """``split_camera_thresholds``'s report (its ``part_scores``, ``splits`` and ``chosen``) as a scatter on logit
    axes (the decision scores crowd near 0 and 1, where the thresholds are): good parts grey, defective parts
    coloured by type, the chosen thresholds as lines and each camera's threshold alone dotted."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    parts = report["part_scores"]
    chosen = report["splits"][report["chosen"]]

    def clip(v: float) -> float:
        return float(np.clip(v, EDGE, 1 - EDGE))

    fig, ax = plt.subplots(figsize=(5.6, 5))
    good = [p for p in parts if not p["defective"]]
    ax.scatter([clip(p["first"]) for p in good], [clip(p["second"]) for p in good], s=6, c="0.6",
               label=f"good ({len(good)})")
    for t in sorted({p["defect_type"] or "?" for p in parts if p["defective"]}):
        some = [p for p in parts if p["defective"] and (p["defect_type"] or "?") == t]
        ax.scatter([clip(p["first"]) for p in some], [clip(p["second"]) for p in some], s=9, label=f"{t} ({len(some)})")
    ax.set_xscale("logit")
    ax.set_yscale("logit")
    ax.axvline(clip(chosen["first"]), color="k", lw=1)
    ax.axhline(clip(chosen["second"]), color="k", lw=1)
    for name, draw in (("first", ax.axvline), ("second", ax.axhline)):
        alone = report["alone"][name]["threshold"]
        draw(clip(alone), color="k", lw=0.8, ls=":")
    ax.set(xlabel="first camera's score", ylabel="second camera's score",
           title=f"split: {chosen['good_rejected']} of {report['good']} good rejected, "
                 f"{100 * chosen['caught']:.1f} % of {report['defective']} defective caught")
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.02, 1), title="solid: the split\ndotted: each alone",
              title_fontsize=7)
    fig.savefig(path, dpi=120, bbox_inches="tight")
    plt.close(fig)
