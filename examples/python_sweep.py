#!/usr/bin/env python3
"""Sweep one scene parameter through the tmdem Python module and plot the result.

The lattice of examples/lattice_constant.toml with its corner particle held at 373.15 K: the bed
warms through the corner, faster the larger the contact conductance. Each value of
thermal.constant_conductance is one run; the plot shows the mean temperature against time.

    PYTHONPATH=build/python /usr/bin/python3 examples/python_sweep.py sweep.png

Result files go to a temporary folder (or --keep DIR); only the PNG named is written.
"""
# %% Setup
import argparse
import pathlib
import sys
import tempfile

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

root = pathlib.Path(__file__).resolve().parent.parent
sys.path.append(str(root / "build" / "python"))  # after PYTHONPATH: a default build
import tmdem

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("png", help="plot file to write")
parser.add_argument("--keep", help="folder for the result files (default: a temporary one)")
args = parser.parse_args()

conductances_W_per_K = [2.5e-4, 5e-4, 1e-3, 2e-3]

# %% Runs
with tempfile.TemporaryDirectory() as scratch:
    folder = pathlib.Path(args.keep or scratch)
    folder.mkdir(parents=True, exist_ok=True)
    curves = []
    for conductance in conductances_W_per_K:
        scene = tmdem.Scene.load(str(root / "examples" / "lattice_constant.toml"))
        scene.set("assign[0].fixed_temperature", True)
        scene.set("thermal.constant_conductance", conductance)
        summary, result = tmdem.run(scene, output=str(folder / f"sweep_{conductance:g}.h5"),
                                    overwrite=True)
        mean_K = result.temperature.mean(axis=1)
        curves.append((conductance, result.times, mean_K))
        print(f"H = {conductance:g} W/K: {summary['thermal']['steps']} steps, "
              f"mean T {mean_K[0]:.3f} -> {mean_K[-1]:.3f} K, "
              f"energy balance error {summary['energy']['balance_error_rel']:.2e}")

# %% Plot
fig, ax = plt.subplots(figsize=(6, 4))
for conductance, times_s, mean_K in curves:
    ax.plot(times_s, mean_K, label=f"H = {conductance:g} W/K")
ax.set_xlabel("time (s)")
ax.set_ylabel("mean temperature (K)")
ax.set_title("4 x 4 x 4 lattice, corner held at 373.15 K")
ax.legend()
fig.tight_layout()
fig.savefig(args.png, dpi=120)
print(f"wrote {args.png}")
