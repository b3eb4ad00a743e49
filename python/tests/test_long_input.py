"""Long keys and values in scene text, overrides and run_experiment: an InputError naming the field,
as the CLI's exit 2, never a crash (issue 35, item 2: the message parsing once overflowed the stack)."""
import pytest

import jellysim

LONG = "x" * 100000


def test_long_key_in_scene_text():
    with pytest.raises(jellysim.InputError) as e:
        jellysim.load_scene(LONG + " = 1\n")
    assert e.value.field is None or e.value.field.startswith("x")


def test_long_override_key_is_named():
    with pytest.raises(jellysim.InputError) as e:
        jellysim.load_scene(overrides={"x" * 50000: 1})
    assert e.value.field == "x" * 50000


def test_long_override_value():
    with pytest.raises(jellysim.InputError) as e:
        jellysim.load_scene(overrides={"tank.solver": "in (" + LONG})
    assert e.value.field == "tank.solver"


def test_long_key_in_run_experiment(tmp_path):
    with pytest.raises(jellysim.InputError):
        jellysim.run_experiment("simulate", out=tmp_path / "bad", overrides={LONG: 1})
    assert not (tmp_path / "bad").exists()
