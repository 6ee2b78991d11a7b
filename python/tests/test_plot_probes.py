# examples/plot_probes.py on hand-made curves: a probe whose mean temperature rises linearly
# against a measured curve offset by a known amount gives that offset as the RMS, reference
# points outside the run are skipped, and the plot is a PNG written only where told.
import subprocess
import sys


def write(path, text):
    path.write_text(text)
    return path


def test_rms_and_last_point_against_hand_values(tmp_path, source_dir):
    # The model: 293.15 K + 0.01 K/s over 0..100 s, frames every 50 s (linear, so interpolation
    # between frames is exact): 20 C, 20.5 C, 21 C.
    probes = write(tmp_path / "run.csv",
                   "time_s,probe,count,mean_K,min_K,max_K\n"
                   "0,tc,3,293.15,293.15,293.15\n50,tc,3,293.65,293.6,293.7\n"
                   "100,tc,3,294.15,294.1,294.2\n")
    # Measured 0.3 C above the model at 10 and 60 s, 0.4 C below at 90 s; 150 s is outside the run.
    measured = write(tmp_path / "measured.csv", "t,T\n10,20.4\n60,20.9\n90,20.5\n150,30.0\n")
    png = tmp_path / "out" / "plot.png"
    (tmp_path / "out").mkdir()
    out = subprocess.run([sys.executable, str(source_dir / "examples" / "plot_probes.py"),
                          str(probes), "--reference", f"tc={measured}", "-o", str(png)],
                         check=True, capture_output=True, text=True).stdout.splitlines()
    assert out[0] == "run,probe,T_model_C,T_measured_C,time_s,rms_K"
    run, probe, model, T, t, rms = out[1].split(",")
    assert (run, probe, t) == ("run", "tc", "90")
    assert float(model) == 20.9 and float(T) == 20.5
    assert abs(float(rms) - ((0.3**2 + 0.3**2 + 0.4**2) / 3) ** 0.5) < 0.005
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["measured.csv", "out", "run.csv"]


def test_a_reference_for_a_missing_probe_is_refused(tmp_path, source_dir):
    probes = write(tmp_path / "run.csv", "time_s,probe,count,mean_K,min_K,max_K\n0,tc,1,300,300,300\n")
    measured = write(tmp_path / "m.csv", "t,T\n0,27\n")
    r = subprocess.run([sys.executable, str(source_dir / "examples" / "plot_probes.py"),
                        str(probes), "--reference", f"other={measured}"], capture_output=True, text=True)
    assert r.returncode != 0
    assert "no probe other" in r.stderr
