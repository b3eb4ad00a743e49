"""jellysim.load_scene: the CLI's resolution (built-in scene, file or TOML text, overrides) and its
validation, with InputError naming the field and the allowed range."""
import pytest

import jellysim
from conftest import run_cli


def test_builtin_scene_is_simulates():
    scene = jellysim.load_scene()
    assert scene.config["jellyfish"]["frequency"] == 0.7
    assert scene.frame_interval == pytest.approx(1 / 30)


def test_overrides_and_toml_text():
    scene = jellysim.load_scene("[jellyfish]\nfrequency = 0.9\n", overrides={"tank.cells": [48, 96], "output.vtk": False})
    assert scene.config["jellyfish"]["frequency"] == 0.9
    assert scene.config["tank"]["cells"] == [48, 96]
    assert scene.config["output"]["vtk"] is False


def test_scene_file(tmp_path):
    path = tmp_path / "slow.toml"
    path.write_text('scene = "jellyfish"\nduration = 2.0\n[jellyfish]\nfrequency = 0.5\n')
    for source in (path, str(path)):
        scene = jellysim.load_scene(source)
        assert scene.duration == 2.0
        assert scene.config["jellyfish"]["frequency"] == 0.5


def test_bad_override_names_the_field_and_range():
    with pytest.raises(jellysim.InputError) as e:
        jellysim.load_scene(overrides={"jellyfish.frequency": 7.0})
    assert isinstance(e.value, ValueError)
    assert e.value.field == "jellyfish.frequency"
    assert e.value.range == "(0, 5]"
    assert "jellyfish.frequency" in str(e.value)


def test_unknown_field_is_named():
    with pytest.raises(jellysim.InputError) as e:
        jellysim.load_scene(overrides={"jellyfish.frequencey": 0.9})
    assert e.value.field == "jellyfish.frequencey"


def test_wrong_scene_kind():
    with pytest.raises(jellysim.InputError, match="expected a jellyfish scene"):
        jellysim.load_scene('scene = "swinging-bar"\n')


def test_scene_cannot_be_overridden():
    with pytest.raises(jellysim.InputError, match="--set scene"):
        jellysim.load_scene(overrides={"scene": "swinging-bar"})


def test_messages_are_the_clis(jellysim_bin, tmp_path):
    cli = run_cli(jellysim_bin, "simulate", "--set", "jellyfish.frequency=7", "--out", str(tmp_path),
                  capture_output=True, text=True)
    assert cli.returncode == 2
    with pytest.raises(jellysim.InputError) as e:
        jellysim.load_scene(overrides={"jellyfish.frequency": 7})
    assert cli.stderr.strip() == "jellysim: error: " + e.value.message


def test_missing_file():
    with pytest.raises(jellysim.InputError, match="cannot read scene file"):
        jellysim.load_scene("no/such/scene.toml")
