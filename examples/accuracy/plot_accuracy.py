#!/usr/bin/python3
"""Work-precision plot of a `tmdem study accuracy` CSV.

Reads the CSV (header method,linear_solver,parameter,max_error_K,wall_time_s,steps,rhs_evals,
status,predicted_wall_time_s: the contract's seven columns and tmdem's two) and draws the max error at the end time against the wall time, log-log, one line per method and
linear solver (explicit: one point per step; cvode/ida: one point per relative tolerance), with
the 1e-3 K and 1e-6 K targets as dashed lines. Saves a PNG.

Example:
    tmdem study accuracy stiff_bed.toml --csv stiff_bed.csv
    ./plot_accuracy.py stiff_bed.csv -o stiff_bed.png --title "stiff bed (800 particles)"
"""
import argparse
import csv
import os
import sys
from collections import OrderedDict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

HEADER = ["method", "linear_solver", "parameter", "max_error_K", "wall_time_s", "steps", "rhs_evals"]
EXTENSION = ["status", "predicted_wall_time_s"]  # tmdem's two columns (the runs skipped: OUT.skipped.csv)
STYLE = {
    "explicit": dict(color="black", marker="o"),
    "cvode/klu": dict(color="tab:blue", marker="s"),
    "cvode/pcg": dict(color="tab:cyan", marker="^"),
    "ida/klu": dict(color="tab:red", marker="D"),
    "ida/pcg": dict(color="tab:orange", marker="v"),
}
FLOOR = 1e-16  # an error or time of exactly 0 is drawn here (log axes)


def read_runs(path):
    with open(path, newline="") as f:
        reader = csv.reader(f)
        header = next(reader, None)
        if header not in (HEADER, HEADER + EXTENSION):
            raise ValueError(f"{path}: expected the header {','.join(HEADER + EXTENSION)}, got {header}")
        series = OrderedDict()
        for row in reader:
            if not row or (len(row) > 7 and row[7] != "ok"):
                continue  # older CSVs listed skipped runs here, with no error nor time to draw
            method, solver, parameter, error, wall = row[0], row[1], float(row[2]), float(row[3]), float(row[4])
            label = method if method == "explicit" else f"{method}/{solver}"
            series.setdefault(label, []).append((wall, error, parameter))
    return series


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("csv", help="CSV written by tmdem study accuracy --csv")
    parser.add_argument("-o", "--output", help="PNG file (default: the CSV name with .png)")
    parser.add_argument("--title", help="plot title (default: the CSV file name)")
    parser.add_argument("--annotate", action="store_true",
                        help="label the explicit points with their step (s) and the first implicit "
                             "method's points with their relative tolerance (the other implicit "
                             "methods run the same tolerances in the same order)")
    args = parser.parse_args(argv)

    try:
        series = read_runs(args.csv)
    except (OSError, ValueError) as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    if not series:
        print(f"error: {args.csv}: no runs", file=sys.stderr)
        return 2
    output = args.output or os.path.splitext(args.csv)[0] + ".png"

    fig, ax = plt.subplots(figsize=(8, 5.5), dpi=120)
    first_implicit = next((label for label in series if label != "explicit"), None)
    for label, points in series.items():
        points.sort(key=lambda p: p[2], reverse=True)  # coarse to fine
        x = [max(p[0], FLOOR) for p in points]
        y = [max(p[1], FLOOR) for p in points]
        style = STYLE.get(label, dict(marker="x"))
        ax.loglog(x, y, label=label, linewidth=1.5, markersize=6, **style)
        if args.annotate and label in ("explicit", first_implicit):
            for xi, yi, p in zip(x, y, (p[2] for p in points)):
                ax.annotate(f"rtol {p:.0e}" if label != "explicit" else f"h={p:.1e} s", (xi, yi),
                            textcoords="offset points",
                            xytext=(4, 4) if label == "explicit" else (-6, -2),
                            ha="left" if label == "explicit" else "right", fontsize=7,
                            color=style.get("color", "gray"))
    for target in (1e-3, 1e-6):
        ax.axhline(target, color="gray", linestyle="--", linewidth=1)
        ax.text(ax.get_xlim()[0], target, f" {target:g} K", va="bottom", ha="left", fontsize=8, color="gray")
    ax.set_xlabel("wall time of initialize + advance (s)")
    ax.set_ylabel("max |T - T_ref| over particles at the end time (K)")
    ax.set_title(args.title or os.path.basename(args.csv))
    ax.grid(True, which="major", alpha=0.4)
    ax.grid(True, which="minor", alpha=0.12)
    ax.legend(title="method / linear solver")
    fig.tight_layout()
    try:
        fig.savefig(output)
    except OSError as e:
        print(f"error: cannot write {output}: {e}", file=sys.stderr)
        return 4
    print(f"wrote {output}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
