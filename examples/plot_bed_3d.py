#!/usr/bin/env python3
"""Temperature plots for 3D beds from a tmdem result file (format tmdem-result-1).

Writes, next to the OUT prefix you give (nothing else is written):
  OUT_height.png  temperature against height: per layer the mean (line) and the spread
                  (band from the coldest to the hottest particle of the layer), one curve per
                  chosen time
  OUT_slice.png   a slice through the bed at one frame: every particle the plane cuts, drawn as
                  the circle of the cut, coloured by temperature
  OUT_layers.csv  with --csv: time_s, layer, height_min_m, height_max_m, count, mean_K, min_K,
                  max_K, std_K (the numbers the first plot draws)

Height is measured along -gravity of the stored scene (along y when gravity is zero), or
along --axis. Layers are --layers equal bins of particle centre heights. The slice is normal to
--slice-axis (default: the horizontal axis that is not x, i.e. z when height is y) through the
centre of the particle nearest the middle of the bed, or at --slice-at (m).

Needs python3 with numpy, h5py and matplotlib (Debian: python3-h5py python3-matplotlib).

Example:
  plot_bed_3d.py result.h5 -o plots/bed --times 0 10 60 --layers 12
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
    sys.exit(f"plot_bed_3d.py needs numpy, h5py and matplotlib: {error}")

try:
    import tomllib
except ImportError:  # pragma: no cover - python < 3.11
    tomllib = None

AXES = "xyz"


def text(value):
    return value.decode("utf-8") if isinstance(value, bytes) else str(value)


def read_result(path):
    """Times [F], positions [F, N, 3], temperatures [F, N], radii [N], the scene's gravity."""
    with h5py.File(path, "r") as f:
        if text(f.attrs.get("format", "")) != "tmdem-result-1":
            sys.exit(f"{path}: not a tmdem result file (format is not tmdem-result-1)")
        # Only complete frames: contact_offset has one row more than the frames written.
        frames = min(len(f["frames/time"]), len(f["frames/contact_offset"]) - 1)
        if frames < 1:
            sys.exit(f"{path}: no complete frame")
        times = f["frames/time"][:frames]
        position = f["frames/position"][:frames]
        temperature = f["frames/temperature"][:frames]
        radius = f["particles/radius"][:]
        gravity = [0.0, 0.0, 0.0]
        if tomllib is not None:
            scene = tomllib.loads(text(f.attrs.get("scene", "")))
            gravity = scene.get("simulation", {}).get("gravity", gravity)
    return times, position, temperature, radius, np.asarray(gravity, dtype=float)


def height_axis(gravity, requested):
    """Index and sign of the height axis: along -gravity's largest component, else y."""
    if requested:
        return AXES.index(requested), 1.0
    if not np.any(gravity):
        return 1, 1.0
    k = int(np.argmax(np.abs(gravity)))
    return k, -float(np.sign(gravity[k]))


def frame_indices(times, wanted):
    """The frames closest to the wanted times (default: 6 spread over the run), no repeats."""
    if not wanted:
        wanted = np.linspace(times[0], times[-1], min(6, len(times)))
    out = []
    for t in wanted:
        k = int(np.argmin(np.abs(times - t)))
        if k not in out:
            out.append(k)
    return out


def layer_table(heights, temperature_row, edges):
    """Per layer: (lo, hi, count, mean, min, max, std); empty layers are left out."""
    rows = []
    which = np.clip(np.digitize(heights, edges[1:-1]), 0, len(edges) - 2)
    for layer in range(len(edges) - 1):
        T = temperature_row[which == layer]
        if len(T) == 0:
            continue
        rows.append((layer, edges[layer], edges[layer + 1], len(T), T.mean(), T.min(), T.max(),
                     T.std()))
    return rows


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("result", help="tmdem result file (.h5)")
    p.add_argument("-o", "--output", required=True,
                   help="prefix of the files to write, e.g. plots/bed -> plots/bed_height.png")
    p.add_argument("--times", type=float, nargs="*", help="times (s) to draw; default 6 spread")
    p.add_argument("--layers", type=int, default=10, help="number of height layers (default 10)")
    p.add_argument("--axis", choices=list(AXES), help="height axis (default: against gravity)")
    p.add_argument("--slice-axis", choices=list(AXES), help="normal of the slice plane")
    p.add_argument("--slice-at", type=float, help="position of the slice plane (m)")
    p.add_argument("--frame", type=int, default=-1, help="frame of the slice (default: last)")
    p.add_argument("--csv", action="store_true", help="also write OUT_layers.csv")
    args = p.parse_args(argv)
    if args.layers < 1:
        p.error("--layers must be at least 1")

    times, position, temperature, radius, gravity = read_result(args.result)
    up, sign = height_axis(gravity, args.axis)
    folder = os.path.dirname(args.output)
    if folder:
        os.makedirs(folder, exist_ok=True)

    # Temperature against height, per chosen frame.
    frames = frame_indices(times, args.times)
    all_heights = sign * position[:, :, up]
    edges = np.linspace(all_heights.min(), all_heights.max(), args.layers + 1)
    if edges[-1] == edges[0]:
        edges = np.array([edges[0] - 0.5, edges[0] + 0.5])
    fig, ax = plt.subplots(figsize=(6, 5))
    colours = plt.cm.viridis(np.linspace(0, 1, len(frames)))
    csv_rows = []
    for colour, k in zip(colours, frames):
        rows = layer_table(all_heights[k], temperature[k], edges)
        centre = np.array([0.5 * (r[1] + r[2]) for r in rows])
        ax.plot([r[4] for r in rows], centre, "-o", ms=3, color=colour, label=f"t = {times[k]:g} s")
        ax.fill_betweenx(centre, [r[5] for r in rows], [r[6] for r in rows], color=colour, alpha=0.2)
        csv_rows += [(times[k],) + r for r in rows]
    ax.set_xlabel("temperature (K): layer mean, band = coldest to hottest particle")
    ax.set_ylabel(f"height along {'-' if sign < 0 else ''}{AXES[up]} (m)")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(args.output + "_height.png", dpi=120)
    plt.close(fig)
    if args.csv:
        with open(args.output + "_layers.csv", "w") as out:
            out.write("time_s,layer,height_min_m,height_max_m,count,mean_K,min_K,max_K,std_K\n")
            for row in csv_rows:
                out.write(",".join(repr(float(v)) if isinstance(v, (float, np.floating)) else str(v)
                                   for v in row) + "\n")

    # A slice through the bed at one frame.
    k = args.frame if args.frame >= 0 else len(times) + args.frame
    if not 0 <= k < len(times):
        sys.exit(f"--frame {args.frame}: the file has frames 0 to {len(times) - 1}")
    normal = AXES.index(args.slice_axis) if args.slice_axis else [a for a in (2, 0, 1) if a != up][0]
    if normal == up:
        sys.exit("--slice-axis: the slice must be upright (its normal is not the height axis)")
    x = position[k]
    if args.slice_at is not None:
        at = args.slice_at
    else:  # through the centre of the particle nearest the middle: its layer is cut whole
        middle = 0.5 * (x[:, normal].min() + x[:, normal].max())
        at = x[int(np.argmin(np.abs(x[:, normal] - middle))), normal]
    distance = np.abs(x[:, normal] - at)
    cut = distance < radius
    across = [a for a in range(3) if a not in (normal, up)][0]
    fig, ax = plt.subplots(figsize=(6, 5))
    circles = [Circle((x[i, across], sign * x[i, up]), np.sqrt(radius[i] ** 2 - distance[i] ** 2))
               for i in np.flatnonzero(cut)]
    patches = PatchCollection(circles, cmap="inferno")
    patches.set_array(temperature[k][cut])
    ax.add_collection(patches)
    if circles:
        ax.set_xlim(x[cut, across].min() - radius.max(), x[cut, across].max() + radius.max())
        ax.set_ylim((sign * x[cut, up]).min() - radius.max(), (sign * x[cut, up]).max() + radius.max())
    ax.set_aspect("equal")
    ax.set_xlabel(f"{AXES[across]} (m)")
    ax.set_ylabel(f"height along {'-' if sign < 0 else ''}{AXES[up]} (m)")
    ax.set_title(f"{AXES[normal]} = {at:.4g} m, t = {times[k]:g} s, {int(cut.sum())} particles cut")
    fig.colorbar(patches, ax=ax, label="temperature (K)")
    fig.tight_layout()
    fig.savefig(args.output + "_slice.png", dpi=120)
    plt.close(fig)
    print(f"wrote {args.output}_height.png ({len(frames)} times, {len(edges) - 1} layers), "
          f"{args.output}_slice.png ({int(cut.sum())} particles)"
          + (f", {args.output}_layers.csv" if args.csv else ""))


if __name__ == "__main__":
    main()
