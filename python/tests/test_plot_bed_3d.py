# examples/plot_bed_3d.py on a 4 x 4 x 4 lattice: its layer table equals the layer statistics
# computed here from the result file (and, at t = 0, by hand); it writes only where told.
import csv
import os
import subprocess
import sys

import h5py
import numpy as np


def test_layers_and_slice(tmp_path, source_dir, tmdem_binary, lattice_scene):
    result = tmp_path / "lattice.h5"
    subprocess.run([str(tmdem_binary), "run", str(lattice_scene), "-o", str(result), "--quiet",
                    "--set", "simulation.duration=20", "--set", "output.interval=10"], check=True)
    before = sorted(os.listdir(source_dir / "examples"))
    out = tmp_path / "plots" / "bed"
    printed = subprocess.run([sys.executable, str(source_dir / "examples" / "plot_bed_3d.py"),
                              str(result), "-o", str(out), "--layers", "4", "--times", "0", "20",
                              "--csv"], check=True, capture_output=True, text=True).stdout
    assert sorted(os.listdir(source_dir / "examples")) == before
    for name in ("bed_height.png", "bed_slice.png"):
        assert (tmp_path / "plots" / name).read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    # The default slice goes through the centres of one z layer of the lattice: 16 spheres.
    assert "bed_slice.png (16 particles)" in printed

    with open(str(out) + "_layers.csv") as f:
        rows = list(csv.DictReader(f))
    assert len(rows) == 8  # 2 times x 4 layers (y = 1, 3, 5, 7 mm)
    with h5py.File(result, "r") as f:
        times = f["frames/time"][:]
        y = f["frames/position"][0, :, 1]
        T = f["frames/temperature"][:]
    levels = np.unique(np.round(y, 9))
    for row in rows:
        k = int(np.argmin(np.abs(times - float(row["time_s"]))))
        layer = int(row["layer"])
        chosen = np.isclose(y, levels[layer], rtol=0, atol=1e-9)
        assert int(row["count"]) == chosen.sum() == 16
        assert float(row["mean_K"]) == np.mean(T[k, chosen])
        assert float(row["min_K"]) == T[k, chosen].min()
        assert float(row["max_K"]) == T[k, chosen].max()
    # t = 0 by hand: particle 0 (bottom layer) at 373.15 K, all others at 293.15 K.
    first = rows[0]
    assert float(first["time_s"]) == 0.0 and first["layer"] == "0"
    assert abs(float(first["mean_K"]) - (293.15 + 80.0 / 16)) < 1e-12
    assert float(first["max_K"]) == 373.15
    assert float(rows[1]["max_K"]) == 293.15
