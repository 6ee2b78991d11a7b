# The reader's arrays obey the lumped energy balance: sum_i C_i T_i changes by exactly the heat
# that entered through the boundary (/frames/boundary_heat), with C_i = m_i c_i computed here
# from the scene's material, independently of the file's heat_capacity.
import math

import numpy as np

import tmdem

STEEL_C = 7800.0 * 4.0 / 3.0 * math.pi * 0.001**3 * 460.0  # J/K, one 1 mm steel sphere


def _energy_J(result, frame):
    return float(np.sum(np.full(result.radius.shape, STEEL_C) * result.temperature[frame]))


def test_heat_capacity_is_m_c(tmp_path, lattice_scene):
    scene = tmdem.Scene.load(str(lattice_scene), set=["simulation.duration=1"])
    _, result = tmdem.run(scene, output=str(tmp_path / "r.h5"))
    np.testing.assert_allclose(result.heat_capacity, STEEL_C, rtol=1e-12)


def test_insulated_lattice_conserves_energy(tmp_path, lattice_scene):
    scene = tmdem.Scene.load(str(lattice_scene))
    _, result = tmdem.run(scene, output=str(tmp_path / "r.h5"))
    assert np.all(result.boundary_heat == 0.0)
    first, last = _energy_J(result, 0), _energy_J(result, -1)
    assert abs(last - first) <= 1e-9 * first
    # The heat spread: the hot corner is within 1 K of the mean by t = 50 s (time constant 15 s).
    assert result.temperature[-1, 0] - result.temperature[-1].mean() > 0.0
    assert result.temperature[-1].max() - result.temperature[-1].min() < \
        0.5 * (result.temperature[0].max() - result.temperature[0].min())


def test_held_corner_heat_equals_boundary_heat(tmp_path, lattice_scene):
    # The corner held at 373.15 K is an isothermal boundary: what the others gain came through it.
    # The explicit update sums the boundary heat of the very steps it takes, so the balance holds
    # to round-off (measured 1.0e-14); CVODE integrates boundary_heat as its own quantity within
    # its tolerance (1.8e-6 of it at relative_tolerance 1e-6).
    scene = tmdem.Scene.load(str(lattice_scene))
    scene.set("assign[0].fixed_temperature", True)
    scene.set("thermal.integrator", "explicit")
    _, result = tmdem.run(scene, output=str(tmp_path / "r.h5"))
    gained = _energy_J(result, -1) - _energy_J(result, 0)
    assert gained > 1.0  # J: the bed warmed noticeably
    assert abs(gained - result.boundary_heat[-1]) <= 1e-9 * abs(result.boundary_heat[-1])
    assert np.all(result.temperature[:, 0] == 373.15)
