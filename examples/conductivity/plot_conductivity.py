#!/usr/bin/env python3
"""Plot the CSV of `tmdem study conductivity` (columns: docs/conductivity-study.md).

With loads (pressure_Pa filled): k_eff against pressure on log-log axes, with the fitted power
law exponent (and k_bulk where the bed has a bulk). Without: the share of the heat transport each mode carries, one bar group per row.

    /usr/bin/python3 examples/conductivity/plot_conductivity.py k.csv [-o k.png]
"""
import argparse
import csv
import math

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("csv")
    parser.add_argument("-o", "--output", help="image file (default: CSV name with .png)")
    args = parser.parse_args()
    with open(args.csv, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        raise SystemExit(f"{args.csv}: no rows")
    output = args.output or args.csv.rsplit(".", 1)[0] + ".png"
    fig, ax = plt.subplots(figsize=(6, 4))
    loaded = [r for r in rows if r["pressure_Pa"]]
    if loaded:
        p = [float(r["pressure_Pa"]) for r in loaded]
        k = [float(r["k_eff_W_per_mK"]) for r in loaded]
        ax.loglog(p, k, "o-", label="tmdem, between the walls")
        # The bulk (docs/conductivity-study.md "The bulk"), where the bed is deep enough to have one.
        bulk = [(v, float(r["k_bulk_W_per_mK"])) for v, r in zip(p, loaded) if r.get("k_bulk_W_per_mK")]
        if bulk:
            ax.loglog([v for v, _ in bulk], [b for _, b in bulk], "s-", label="tmdem, bulk")
        # Hertz at a fixed contact network: every conductance goes as F^(1/3).
        ax.loglog(p, [k[0] * (v / p[0]) ** (1.0 / 3.0) for v in p], "--", color="gray",
                  label="p^(1/3) through the first point")
        ax.legend(fontsize=8)
        if len(p) > 1:
            lp, lk = [math.log(v) for v in p], [math.log(v) for v in k]
            mp, mk = sum(lp) / len(lp), sum(lk) / len(lk)
            slope = sum((a - mp) * (b - mk) for a, b in zip(lp, lk)) / sum((a - mp) ** 2 for a in lp)
            ax.set_title(f"k_eff ~ p^{slope:.3f}")
        ax.set_xlabel("pressure (Pa)")
        ax.set_ylabel("k_eff (W/(m K))")
    else:
        modes = [c[len("share_"):] for c in rows[0] if c.startswith("share_")]
        modes = [m for m in modes if any(float(r["share_" + m]) != 0.0 for r in rows)]
        width = 0.8 / max(len(rows), 1)
        for i, r in enumerate(rows):
            ax.bar([j + i * width for j in range(len(modes))],
                   [float(r["share_" + m]) for m in modes], width,
                   label=f"k_eff = {float(r['k_eff_W_per_mK']):.4g} W/(m K), "
                         f"porosity {float(r['porosity']):.3f}"
                         + (f"; bulk {float(r['k_bulk_W_per_mK']):.4g}"
                            if r.get("k_bulk_W_per_mK") else ""))
        ax.set_xticks(range(len(modes)))
        ax.set_xticklabels(modes)
        ax.set_ylabel("share of the heat transport")
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(output, dpi=120)
    print(f"wrote {output}")


if __name__ == "__main__":
    main()
