# The module runs the same code path as `tmdem run`: same scene, same overrides -> the same
# result file bit for bit, and the same summary apart from wall times.
import json
import tomllib
import subprocess

import numpy as np

import tmdem

ARRAYS = ["times", "temperature", "position", "velocity", "thermal_energy", "boundary_heat",
          "radius", "mass", "heat_capacity", "material", "contact_offset", "pair",
          "normal_force", "tangential_force", "conductance", "heat_flow"]


def _without_wall_times(summary):
    summary = json.loads(json.dumps(summary))
    summary.pop("wall_time_s")
    summary["thermal"].pop("wall_time_s", None)
    summary.pop("wall_time_parts", None)  # where the wall time went: timing, like the above
    # How idle OpenMP threads waited: the program sets "passive" for itself, the module runs in
    # Python's process as the user started it; it changes timings only, never the bits.
    summary.pop("openmp", None)
    return summary


def test_lattice_run_matches_program_bit_for_bit(tmp_path, tmdem_binary, lattice_scene):
    sets = ["output.interval=2.5", "simulation.duration=20"]
    program_h5, program_json = tmp_path / "program.h5", tmp_path / "program.json"
    subprocess.run([str(tmdem_binary), "run", str(lattice_scene), "--quiet", "-o", str(program_h5),
                    "--summary", str(program_json)] + sum([["--set", s] for s in sets], []),
                   check=True)

    scene = tmdem.Scene.load(str(lattice_scene))
    scene.set("output.interval", 2.5)
    scene.set("simulation.duration", "20")
    summary, result = tmdem.run(scene, output=str(tmp_path / "python.h5"),
                                summary=str(tmp_path / "python.json"))
    program = tmdem.Result(str(program_h5))

    assert result.status == program.status == "ok"
    assert result.frames == program.frames == 9  # t = 0, 2.5, ..., 20
    assert result.temperature.shape == (9, 64) and result.position.shape == (9, 64, 3)
    # The same resolved scene, each naming the file it wrote (output= and -o set output.file).
    ours_scene, theirs_scene = tomllib.loads(result.scene), tomllib.loads(program.scene)
    assert ours_scene["output"].pop("file") == str(tmp_path / "python.h5")
    assert theirs_scene["output"].pop("file") == str(program_h5)
    assert ours_scene == theirs_scene
    for name in ARRAYS:
        ours, theirs = getattr(result, name), getattr(program, name)
        assert ours.dtype == theirs.dtype and ours.shape == theirs.shape, name
        assert np.array_equal(ours, theirs), name
    # The run really moved heat: the hot corner cooled.
    assert result.temperature[-1, 0] < result.temperature[0, 0] - 1.0
    program_summary = json.loads(program_json.read_text())
    assert _without_wall_times(summary) == _without_wall_times(program_summary)
    assert _without_wall_times(json.loads((tmp_path / "python.json").read_text())) == \
        _without_wall_times(program_summary)


def test_contacts_per_frame(tmp_path, lattice_scene):
    scene = tmdem.Scene.load(str(lattice_scene), set=["simulation.duration=1"])
    _, result = tmdem.run(scene, output=str(tmp_path / "r.h5"))
    # 4 x 4 x 4 touching lattice: 3 * 4 * 4 * 3 = 144 face contacts, all of conductance 1e-3 W/K.
    for frame in range(result.frames):
        contacts = result.contacts(frame)
        assert contacts["pair"].shape == (144, 2)
        assert np.all(contacts["conductance"] == 1.0e-3)
        assert np.all(contacts["pair"][:, 0] < contacts["pair"][:, 1])
    last = result.contacts(-1)
    assert np.array_equal(last["pair"], result.pair[result.contact_offset[-2]:])


def test_heat_flow_is_conductance_times_temperature_difference(tmp_path, lattice_scene):
    # The lattice's hot corner loses heat to its neighbours: every contact carries
    # H (T_i - T_j) at its frame's temperatures, recomputed here from the stored arrays.
    scene = tmdem.Scene.load(str(lattice_scene), set=["simulation.duration=5"])
    _, result = tmdem.run(scene, output=str(tmp_path / "r.h5"))
    for frame in range(result.frames):
        contacts = result.contacts(frame)
        i, j = contacts["pair"][:, 0], contacts["pair"][:, 1]
        assert np.all(j >= 0)  # particle pairs only in this scene
        T = result.temperature[frame]
        expected = contacts["conductance"] * (T[i] - T[j])
        assert np.array_equal(contacts["heat_flow"], expected), frame
    assert np.max(result.contacts(0)["heat_flow"]) > 0.0  # the corner really sends heat


def test_existing_file_refused_without_overwrite(tmp_path, lattice_scene):
    scene = tmdem.Scene.load(str(lattice_scene), set=["simulation.duration=1"])
    path = str(tmp_path / "r.h5")
    tmdem.run(scene, output=path)
    try:
        tmdem.run(scene, output=path)
    except tmdem.RunError as error:
        assert error.args[1] == 2 and "r.h5" in error.args[0]
    else:
        raise AssertionError("second run without overwrite was not refused")
    summary, _ = tmdem.run(scene, output=path, overwrite=True)
    assert summary["status"] == "ok"
