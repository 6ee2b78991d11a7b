#!/usr/bin/env python3
"""Plot a thermal cycling run (effects.mechanics = "coupled", examples/thermal_cycling.toml).

Reads a tmdem result file (format tmdem-result-1) and writes PREFIX.png with three panels
against time (s): the mean particle temperature (K); the bed height, the lid's point along its
normal (m, /frames/wall_position of the lid wall); and each wall's force (N, /frames/wall_force:
the sum of the normal forces of its contacts at each frame; older files: summed from the
/contacts rows with j < 0, wall -1 - j). It also
prints one line per cycle: the bed height and the side walls' largest force at the end of the
cycle, which show the ratcheting (the bed settling a little further at each cycle).

Needs python3 with numpy, h5py and matplotlib (Debian: apt install python3-h5py
python3-matplotlib).

Example:
  plot_thermal_cycling.py thermal_cycling.h5 --lid 5 --period 2000 --prefix cycling
"""
import argparse
import sys

try:
    import h5py
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
except ImportError as error:  # pragma: no cover - depends on the machine
    sys.exit(f"plot_thermal_cycling.py needs numpy, h5py and matplotlib: {error}")


def wall_forces(result):
    """Per frame and wall, the sum of the normal forces (N) of the wall's contacts: [F, W].
    /frames/wall_force when the file has it, else summed from /contacts."""
    if "/frames/wall_force" in result:
        return result["/frames/wall_force"][:]
    offset = result["/frames/contact_offset"][:]
    pair = result["/contacts/pair"][:]
    force = result["/contacts/normal_force"][:]
    walls = result["/walls/point"].shape[0]
    out = np.zeros((len(offset) - 1, walls))
    for f in range(len(offset) - 1):
        rows = slice(offset[f], offset[f + 1])
        j = pair[rows, 1]
        on_wall = j < 0
        np.add.at(out[f], -1 - j[on_wall], force[rows][on_wall])
    return out


def read_cycling(path, lid):
    """Times (s), mean temperatures (K), the lid's height along z (m) and wall forces [F, W] (N)."""
    with h5py.File(path, "r") as result:
        time = result["/frames/time"][:]
        temperature = result["/frames/temperature"][:].mean(axis=1)
        height = result["/frames/wall_position"][:, lid, 2]
        forces = wall_forces(result)
    count = min(len(time), len(forces))  # a run still going: its complete frames
    return time[:count], temperature[:count], height[:count], forces[:count]


def per_cycle(time, height, forces, period, side_walls):
    """(cycle, end time, height, largest side-wall force over the cycle) for each whole cycle."""
    rows = []
    cycle = 1
    while cycle * period <= time[-1] + 1e-9 * period:
        end = int(np.argmin(np.abs(time - cycle * period)))
        start = int(np.argmin(np.abs(time - (cycle - 1) * period)))
        largest = forces[start:end + 1, side_walls].max() if side_walls else 0.0
        rows.append((cycle, time[end], height[end], largest))
        cycle += 1
    return rows


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("result", help="result file (HDF5)")
    parser.add_argument("--lid", type=int, required=True, help="index of the lid (piston) wall")
    parser.add_argument("--period", type=float, required=True, help="cycle length, s")
    parser.add_argument("--side-walls", type=int, nargs="*", default=None,
                        help="walls whose force is summarised per cycle (default: all but the "
                             "lid and wall 0)")
    parser.add_argument("--prefix", default="thermal_cycling", help="output PNG prefix")
    args = parser.parse_args(argv)

    time, temperature, height, forces = read_cycling(args.result, args.lid)
    side = args.side_walls if args.side_walls is not None else [
        w for w in range(forces.shape[1]) if w not in (0, args.lid)]
    print("cycle  end_s  bed_height_m  largest_side_wall_force_N")
    for cycle, end, h, largest in per_cycle(time, height, forces, args.period, side):
        print(f"{cycle:5d}  {end:g}  {h:.9f}  {largest:.6g}")

    fig, axes = plt.subplots(3, 1, figsize=(8, 9), sharex=True)
    axes[0].plot(time, temperature)
    axes[0].set_ylabel("mean particle T (K)")
    axes[1].plot(time, height * 1e3)
    axes[1].set_ylabel("bed height, lid (mm)")
    for w in range(forces.shape[1]):
        axes[2].plot(time, forces[:, w], label=f"wall {w}" + (" (lid)" if w == args.lid else ""))
    axes[2].set_ylabel("wall force (N)")
    axes[2].set_xlabel("time (s)")
    axes[2].legend(fontsize="small", ncol=3)
    fig.tight_layout()
    fig.savefig(f"{args.prefix}.png", dpi=110)
    print(f"wrote {args.prefix}.png")
    return 0


if __name__ == "__main__":
    sys.exit(main())
