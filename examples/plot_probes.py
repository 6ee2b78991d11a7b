#!/usr/bin/env python3
"""Probe curves of tmdem runs against measured ones: a plot and the RMS error per probe.

Each RUN is the CSV of `tmdem probes RESULT.h5 -o RUN.csv` (time_s, probe, count, mean_K, ...);
each --reference PROBE=FILE is a measured curve for that probe, a CSV with the columns t (s) and
T (degrees Celsius), the form in which Lethe's example examples/dem-mp/3d-heated-packed-bed
keeps Beaulieu's thermocouples (reference/steel_Beaulieu_0.040_experiment.csv, ...). The mean
temperature of every probe that has a reference is drawn in degrees Celsius against time, the
reference as points; for each run and probe the script prints the model and the measurement at
the last reference time inside the run, and the RMS of model minus measurement over the
reference points (the model linearly interpolated between its frames; reference points outside
the run are skipped).

Needs python3 with matplotlib (Debian: apt install python3-matplotlib).

  plot_probes.py bahrami.csv gas_defaults.csv -o bed.png \\
      --reference tc_0.040=steel_Beaulieu_0.040_experiment.csv \\
      --reference tc_0.060=steel_Beaulieu_0.060_experiment.csv
"""
import argparse
import csv
import math
import os
import sys

KELVIN_AT_0C = 273.15


def read_probes(path):
    """probe name -> ([time_s], [mean temperature in C]) from a `tmdem probes` CSV."""
    series = {}
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            times, values = series.setdefault(row["probe"], ([], []))
            times.append(float(row["time_s"]))
            values.append(float(row["mean_K"]) - KELVIN_AT_0C)
    return series


def read_reference(path):
    """[(t_s, T_C)] of a measured curve (columns t, T)."""
    with open(path, newline="") as f:
        return [(float(row["t"]), float(row["T"])) for row in csv.DictReader(f)]


def interpolate(times, values, t):
    """The model at t, linear between frames; None outside the run."""
    if not times or t < times[0] or t > times[-1]:
        return None
    for k in range(1, len(times)):
        if t <= times[k]:
            w = (t - times[k - 1]) / (times[k] - times[k - 1])
            return values[k - 1] + w * (values[k] - values[k - 1])
    return values[-1]


def compare(times, values, reference):
    """(last reference point inside the run, the model there, RMS over the points inside) or None."""
    inside = [(t, T, interpolate(times, values, t)) for t, T in reference]
    inside = [(t, T, m) for t, T, m in inside if m is not None]
    if not inside:
        return None
    rms = math.sqrt(sum((m - T) ** 2 for _, T, m in inside) / len(inside))
    return inside[-1], rms


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("runs", nargs="+", help="CSV files of `tmdem probes`")
    parser.add_argument("--reference", action="append", default=[], metavar="PROBE=FILE",
                        help="measured curve of PROBE (columns t in s, T in C); repeatable")
    parser.add_argument("-o", "--output", help="PNG to write (default: no plot, the table only)")
    parser.add_argument("--title", default="", help="title of the plot")
    args = parser.parse_args()

    references = {}
    for item in args.reference:
        probe, sep, path = item.partition("=")
        if not sep or not probe or not path:
            sys.exit(f"--reference wants PROBE=FILE (got {item!r})")
        references[probe] = read_reference(path)
    runs = [(os.path.splitext(os.path.basename(p))[0], read_probes(p)) for p in args.runs]
    for name, series in runs:
        missing = [p for p in references if p not in series]
        if missing:
            sys.exit(f"{name}: no probe {', '.join(missing)} (probes: {', '.join(series)})")

    print("run,probe,T_model_C,T_measured_C,time_s,rms_K")
    for name, series in runs:
        for probe, reference in references.items():
            result = compare(*series[probe], reference)
            if result is not None:
                (t, T, model), rms = result
                print(f"{name},{probe},{model:.2f},{T:.2f},{t:g},{rms:.2f}")

    if args.output:
        try:
            import matplotlib
            matplotlib.use("Agg")
            import matplotlib.pyplot as plt
        except ImportError as error:  # pragma: no cover - depends on the machine
            sys.exit(f"plot_probes.py needs matplotlib for the plot: {error}")
        fig, ax = plt.subplots(figsize=(8, 5.5))
        colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
        styles = ["-", "--", ":", "-."]
        for p, (probe, reference) in enumerate(references.items()):
            colour = colours[p % len(colours)]
            ax.plot(*zip(*reference), ".", color=colour, markersize=4, label=f"{probe} measured")
            for r, (name, series) in enumerate(runs):
                ax.plot(*series[probe], styles[r % len(styles)], color=colour, label=f"{probe} {name}")
        ax.set_xlabel("time (s)")
        ax.set_ylabel("temperature (C)")
        if args.title:
            ax.set_title(args.title)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7, ncol=2)
        fig.tight_layout()
        fig.savefig(args.output, dpi=120)
        print(f"wrote {args.output}", file=sys.stderr)


if __name__ == "__main__":
    main()
