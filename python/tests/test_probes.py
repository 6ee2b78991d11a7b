# tmdem.read_probes: the [[probe]] readings of a result file by name. On the lattice example
# (mechanics off, the hot corner particle 0 at the origin corner) a sphere around the corner and
# a box around the first row give, at every frame, the count, mean, min and max of the
# per-particle temperatures the same file stores; a probe off the lattice holds nothing.
import numpy as np

import tmdem

PROBES = """
[[probe]]                         # a sphere of 1.1 mm around particle 0: its neighbours are 2 mm away
name = "corner"
point = [0.001, 0.001, 0.001]
radius = 0.0011

[[probe]]                         # the first row along x: y = z = 1 mm, x = 1, 3, 5, 7 mm
name = "row"
point = [0.004, 0.001, 0.001]
box = [0.008, 0.001, 0.001]

[[probe]]                         # off the lattice: holds nothing
name = "outside"
point = [1.0, 1.0, 1.0]
radius = 0.001
"""


def test_read_probes_matches_stored_temperatures(tmp_path, lattice_scene):
    scene_path = tmp_path / "probes.toml"
    scene_path.write_text(lattice_scene.read_text() + PROBES)
    scene = tmdem.Scene.load(str(scene_path), set=["simulation.duration=2"])
    _, result = tmdem.run(scene, output=str(tmp_path / "r.h5"))
    probes = tmdem.read_probes(str(tmp_path / "r.h5"))
    assert list(probes) == ["corner", "row", "outside"]
    T = result.temperature
    pos = result.position
    frames = len(result.times)
    assert frames == 5
    row = (np.abs(pos[0, :, 1] - 0.001) < 1e-9) & (np.abs(pos[0, :, 2] - 0.001) < 1e-9)
    assert row.sum() == 4
    corner = probes["corner"]
    np.testing.assert_array_equal(corner["time_s"], result.times)
    np.testing.assert_array_equal(corner["count"], np.ones(frames))
    np.testing.assert_array_equal(corner["mean_K"], T[:, 0])
    np.testing.assert_array_equal(corner["min_K"], T[:, 0])
    np.testing.assert_array_equal(corner["max_K"], T[:, 0])
    assert corner["mean_K"][0] == 373.15
    r = probes["row"]
    np.testing.assert_array_equal(r["count"], np.full(frames, 4))
    np.testing.assert_allclose(r["mean_K"], T[:, row].mean(axis=1), rtol=1e-15)
    np.testing.assert_array_equal(r["min_K"], T[:, row].min(axis=1))
    np.testing.assert_array_equal(r["max_K"], T[:, row].max(axis=1))
    assert abs(r["mean_K"][0] - (373.15 + 3 * 293.15) / 4) < 1e-12
    assert r["min_K"][0] == 293.15 and r["max_K"][0] == 373.15
    out = probes["outside"]
    np.testing.assert_array_equal(out["count"], np.zeros(frames))
    for key in ("mean_K", "min_K", "max_K"):
        np.testing.assert_array_equal(out[key], np.zeros(frames))


def test_read_probes_without_probes_is_empty(tmp_path, lattice_scene):
    scene = tmdem.Scene.load(str(lattice_scene), set=["simulation.duration=0.5"])
    tmdem.run(scene, output=str(tmp_path / "r.h5"))
    assert tmdem.read_probes(str(tmp_path / "r.h5")) == {}
