# Scene.set takes keys and values exactly as --set, and refuses what --set refuses.
import pytest

import tmdem


def test_unknown_key_names_the_key(lattice_scene):
    scene = tmdem.Scene.load(str(lattice_scene))
    with pytest.raises(tmdem.SceneError, match=r"thermal\.integratr"):
        scene.set("thermal.integratr", "explicit")
    assert scene.overrides == []  # a refused override leaves the scene as it was


def test_bad_value_names_the_key(lattice_scene):
    scene = tmdem.Scene.load(str(lattice_scene))
    with pytest.raises(ValueError, match=r"thermal\.constant_conductance"):
        scene.set("thermal.constant_conductance", -1.0)
    with pytest.raises(tmdem.SceneError, match=r"thermal\.integrator"):
        scene.set("thermal.integrator", "rk4")


def test_values_as_toml_text_or_python(lattice_scene):
    scene = tmdem.Scene.load(str(lattice_scene))
    scene.set("thermal.integrator", "explicit")
    scene.set("thermal.constant_conductance", 2.5e-3)
    scene.set("generate[0].counts", [2, 3, 4])
    assert scene.particles == 24
    assert scene.overrides == ["thermal.integrator=explicit",
                               "thermal.constant_conductance=0.0025",
                               "generate[0].counts=[2, 3, 4]"]
    assert 'integrator = "explicit"' in scene.toml
    with pytest.raises(TypeError):
        scene.set("simulation.duration", object())


def test_default_scene_and_missing_file(tmp_path):
    assert tmdem.Scene.default().particles > 0
    with pytest.raises(tmdem.SceneError, match="nope.toml"):
        tmdem.Scene.load(str(tmp_path / "nope.toml"))
    with pytest.raises(tmdem.OutputError, match="nope.h5"):
        tmdem.Result(str(tmp_path / "nope.h5"))
