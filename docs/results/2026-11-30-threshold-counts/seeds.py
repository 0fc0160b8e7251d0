"""The shipped file's good parts rejected at its threshold (0.9785) on its seven report seeds, against what its
validation count promises (model.draem.rate_bounds); writes seeds.md and seeds.png. Counts from the model card
(model/weights/README.md) and each check's results page."""
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

from model.draem.rate_bounds import expected_rate, interval, upper_bound

SEEDS = {1165: (0, 176), 1167: (2, 184), 1169: (3, 153), 1170: (1, 172), 1171: (4, 176), 1172: (2, 261),
         1173: (4, 239)}
K, N = 3, 370  # good validation parts above the threshold, of data/line-pv-val's good parts
lines = ["| seed | good parts rejected | share | exact 95 % interval |", "|---|---|---|---|"]
for s, (k, n) in SEEDS.items():
    lo, hi = interval(k, n)
    lines.append(f"| {s} | {k} of {n} | {100 * k / n:.1f} % | {100 * lo:.1f}-{100 * hi:.1f} % |")
k, n = sum(v[0] for v in SEEDS.values()), sum(v[1] for v in SEEDS.values())
lo, hi = interval(k, n)
lines.append(f"| all seven | {k} of {n} | {100 * k / n:.2f} % | {100 * lo:.2f}-{100 * hi:.2f} % |")
lines.append(f"\nPromised by {K} of {N} validation good parts above the threshold: about "
             f"{100 * expected_rate(K, N):.2f} %, at most {100 * upper_bound(K, N):.2f} % at 95 % confidence.")
open("docs/results/2026-11-30-threshold-counts/seeds.md", "w").write("\n".join(lines) + "\n")

fig, ax = plt.subplots(figsize=(6.4, 3.4))
xs = [*range(len(SEEDS)), len(SEEDS) + 0.5]
for x, (label, (kk, nn)) in zip(xs, [*SEEDS.items(), ("all", (k, n))], strict=True):
    lo, hi = interval(kk, nn)
    ax.errorbar(x, 100 * kk / nn, yerr=[[100 * (kk / nn - lo)], [100 * (hi - kk / nn)]], fmt="o",
                color="k" if label == "all" else "C0", capsize=3)
ax.axhline(100 * expected_rate(K, N), color="C2", label=f"expected from {K} of {N}: {100 * expected_rate(K, N):.1f} %")
ax.axhline(100 * upper_bound(K, N), color="C3", ls="--", label=f"95 % bound: {100 * upper_bound(K, N):.1f} %")
ax.axhline(1.0, color="grey", ls=":", label="issue 19's 1 %")
ax.set_xticks(xs, [str(s) for s in SEEDS] + ["all"])
ax.set_ylabel("good parts rejected (%)")
ax.set_xlabel("held-out seed (exact 95 % interval)")
ax.legend(fontsize=7, loc="upper left")
fig.tight_layout()
fig.savefig("docs/results/2026-11-30-threshold-counts.png", dpi=110)
print("\n".join(lines))
