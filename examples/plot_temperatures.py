#!/usr/bin/env python3
"""Plot a tmdem result file (format tmdem-result-1, see CONTRACT.md section 3).

Writes two PNG files:
  PREFIX_temperatures.png  temperature (K) against time (s) for the chosen particles
  PREFIX_positions.png     particles at one frame (default: the last), drawn as circles of
                           their true radius in the xy-plane, coloured by temperature

The file may belong to a run that is still going: every complete frame is shown.

Needs python3 with h5py and matplotlib (Debian/Ubuntu: apt install python3-h5py
python3-matplotlib).

Examples:
  plot_temperatures.py result.h5
  plot_temperatures.py result.h5 --ids 0 17 255 --frame 10 --prefix plots/bed
"""
import argparse
import os
import sys

try:
    import h5py
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.collections import PatchCollection
    from matplotlib.patches import Circle
    import numpy as np
except ImportError as error:  # pragma: no cover - depends on the machine
    sys.exit(f"plot_temperatures.py needs numpy, h5py and matplotlib: {error}")


def text(value):
    """An HDF5 string attribute as str (h5py returns str or bytes depending on storage)."""
    return value.decode("utf-8") if isinstance(value, bytes) else str(value)


def read_result(path, frame):
    """Times, temperatures [F, N], positions [N, 3] and radii of one frame, plus metadata."""
    with h5py.File(path, "r") as f:
        if text(f.attrs.get("format", "")) != "tmdem-result-1":
            raise ValueError(f"{path}: not a tmdem-result-1 file")
        times = f["frames/time"][()]
        frames = len(times)  # written last in each frame: counts complete frames
        if frames == 0:
            raise ValueError(f"{path}: no frames written yet")
        if not -frames <= frame < frames:
            raise ValueError(f"{path}: frame {frame} out of range, the file has {frames} frames")
        frame %= frames
        temperatures = f["frames/temperature"][:frames]
        positions = f["frames/position"][frame]
        radii = f["particles/radius"][()]
        status = text(f.attrs.get("status", "?"))
    return times, temperatures, positions, radii, frame, status


def default_ids(temperatures):
    """The three particles hottest at the start and the three that warmed most by the end:
    where the heat comes from and where it went."""
    hottest = list(temperatures[0].argsort()[::-1][:3])
    warmed = list((temperatures[-1] - temperatures[0]).argsort()[::-1])
    ids = hottest + [i for i in warmed if i not in hottest][:3]
    return sorted(int(i) for i in ids)


def plot_history(times, temperatures, ids, title, out):
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for i in ids:
        ax.plot(times, temperatures[:, i], marker="." if len(times) < 50 else None,
                label=f"particle {i}")
    ax.set_xlabel("time (s)")
    ax.set_ylabel("temperature (K)")
    ax.set_title(title)
    ax.grid(True, alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(out, dpi=150)
    plt.close(fig)


def plot_positions(positions, radii, temperature, title, out):
    fig, ax = plt.subplots(figsize=(7, 6))
    circles = [Circle((x, y), r) for (x, y, _), r in zip(positions, radii)]
    patches = PatchCollection(circles, cmap="inferno", edgecolor="black", linewidth=0.3)
    patches.set_array(np.asarray(temperature))
    ax.add_collection(patches)
    pad = float(radii.max()) if len(radii) else 1.0
    ax.set_xlim(positions[:, 0].min() - pad, positions[:, 0].max() + pad)
    ax.set_ylim(positions[:, 1].min() - pad, positions[:, 1].max() + pad)
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_title(title)
    fig.colorbar(patches, ax=ax, label="temperature (K)")
    fig.tight_layout()
    fig.savefig(out, dpi=150)
    plt.close(fig)


def main(argv=None):
    parser = argparse.ArgumentParser(
        description="Plot temperature histories and a temperature-coloured particle picture "
                    "from a tmdem result file (HDF5).",
        epilog="Output: PREFIX_temperatures.png and PREFIX_positions.png.")
    parser.add_argument("result", help="tmdem result file (.h5)")
    parser.add_argument("--ids", type=int, nargs="+", metavar="ID",
                        help="particle ids for the temperature plot "
                             "(default: the three hottest at the start and the three that "
                             "warmed most)")
    parser.add_argument("--frame", type=int, default=-1,
                        help="frame for the particle picture; negative counts from the end "
                             "(default: -1, the last frame)")
    parser.add_argument("--prefix",
                        help="output path prefix (default: the result file without .h5)")
    args = parser.parse_args(argv)

    try:
        times, temperatures, positions, radii, frame, status = read_result(args.result, args.frame)
    except (OSError, KeyError, ValueError) as error:
        sys.exit(f"plot_temperatures.py: cannot read {args.result}: {error}")
    count = temperatures.shape[1]
    ids = args.ids if args.ids else default_ids(temperatures)
    bad = [i for i in ids if not 0 <= i < count]
    if bad:
        sys.exit(f"plot_temperatures.py: particle ids {bad} out of range 0..{count - 1}")

    prefix = args.prefix or os.path.splitext(args.result)[0]
    folder = os.path.dirname(prefix)
    if folder:
        os.makedirs(folder, exist_ok=True)
    name = os.path.basename(args.result)
    suffix = "" if status == "ok" else f" [status: {status}]"

    history_png = prefix + "_temperatures.png"
    plot_history(times, temperatures, ids, f"{name}: {len(times)} frames{suffix}", history_png)

    flat = np.allclose(positions[:, 2], positions[0, 2]) if count else True
    view = "" if flat else ", projected on xy"
    positions_png = prefix + "_positions.png"
    plot_positions(positions, radii, temperatures[frame],
                   f"{name}: t = {times[frame]:g} s (frame {frame}{view}){suffix}", positions_png)
    print(history_png)
    print(positions_png)


if __name__ == "__main__":
    main()
