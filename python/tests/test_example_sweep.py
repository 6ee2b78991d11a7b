# examples/python_sweep.py runs and writes its plot where told (and nothing into examples/).
import os
import subprocess
import sys


def test_sweep_writes_png(tmp_path, source_dir):
    before = sorted(os.listdir(source_dir / "examples"))
    png = tmp_path / "sweep.png"
    out = subprocess.run([sys.executable, str(source_dir / "examples" / "python_sweep.py"),
                          str(png)], check=True, capture_output=True, text=True).stdout
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert out.count("H = ") == 4
    assert sorted(os.listdir(source_dir / "examples")) == before
