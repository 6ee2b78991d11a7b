# examples/thermal_cycling.toml, shortened to 100 s (two couplings), and
# examples/plot_thermal_cycling.py on its result file: the walls' forces the script sums from
# the result file's contacts are the summary's at the last frame, the lid carries its load
# (pressure x area + weight) at every frame, within what the rest test allows, and the plot is
# a PNG.
import importlib.util
import json
import subprocess
import sys


def load_script(source_dir):
    spec = importlib.util.spec_from_file_location(
        "plot_thermal_cycling", source_dir / "examples" / "plot_thermal_cycling.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_wall_forces_of_a_short_cycling_run(tmp_path, source_dir, tmdem_binary):
    subprocess.run([str(tmdem_binary), "run", str(source_dir / "examples" / "thermal_cycling.toml"),
                    "-o", "c.h5", "--summary", "s.json", "--quiet",
                    "--set", "simulation.duration=100.0", "--set", "output.interval=50.0"],
                   cwd=tmp_path, check=True, env={"OMP_NUM_THREADS": "1"})
    summary = json.loads((tmp_path / "s.json").read_text())
    assert summary["thermo_mechanics"]["couplings"] == 2
    script = load_script(source_dir)
    time, temperature, height, forces = script.read_cycling(tmp_path / "c.h5", lid=5)
    assert list(time) == [0.0, 50.0, 100.0]
    last = summary["thermo_mechanics"]["last_wall_force_N"]
    assert all(abs(a - b) <= 1e-9 * max(1.0, abs(b)) for a, b in zip(forces[-1], last))
    lid_mass_kg = 0.05  # the lid's `mass` in examples/thermal_cycling.toml
    lid_load = 1.0e4 * 1.44e-4 + lid_mass_kg * 9.81  # N: pressure x area + the lid's weight
    # At rest the lid is slower than settle_velocity (1e-4 m/s) on either side of the step, so
    # its contacts carry its load within the change of momentum that allows: 2 m v / h =
    # 2 x 0.05 kg x 1e-4 m/s / 1e-3 s = 0.01 N (0.5% of the load; the runs give 0.02-0.12%).
    lid_bound = 2.0 * lid_mass_kg * 1.0e-4 / 1.0e-3
    for f in forces[:, 5]:
        assert abs(f - lid_load) < lid_bound
    assert abs(height[-1] - summary["thermo_mechanics"]["last_wall_point_m"][17]) < 1e-15
    out = subprocess.run([sys.executable, str(source_dir / "examples" / "plot_thermal_cycling.py"),
                          str(tmp_path / "c.h5"), "--lid", "5", "--period", "50",
                          "--prefix", str(tmp_path / "plot")],
                         check=True, capture_output=True, text=True).stdout.splitlines()
    assert out[0] == "cycle  end_s  bed_height_m  largest_side_wall_force_N"
    assert len(out) == 4  # two whole 50 s "cycles", then the PNG line
    assert (tmp_path / "plot.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
