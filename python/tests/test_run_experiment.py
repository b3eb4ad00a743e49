"""jellysim.run_experiment: the CLI's experiments, overrides as a dict or keywords (__ for .),
summary.json returned as a dict."""
import pytest

import jellysim


def test_simulate_returns_the_summary(tmp_path):
    summary = jellysim.run_experiment("simulate", out=tmp_path, duration=0.1, tank__cells=[48, 96],
                                      output__pictures=False, overrides={"output.vtk": False})
    assert summary["status"] == "ok"
    assert summary["command"] == "simulate"
    assert summary["frames"] == 4
    assert summary["config"]["tank"]["cells"] == [48, 96]
    assert (tmp_path / "metrics.csv").is_file() and (tmp_path / "summary.json").is_file()


def test_bad_keyword_override_names_the_field(tmp_path):
    with pytest.raises(jellysim.InputError) as e:
        jellysim.run_experiment("simulate", out=tmp_path / "bad", jellyfish__gamma=2.0)
    assert e.value.field == "jellyfish.gamma"
    assert not (tmp_path / "bad").exists()  # validated before anything is written


def test_unknown_experiment():
    with pytest.raises(jellysim.InputError, match="unknown experiment 'no-such'"):
        jellysim.run_experiment("no-such")


def test_failed_run_raises_with_the_summary(tmp_path):
    with pytest.raises(jellysim.RunError, match="numerical instability") as e:
        jellysim.run_experiment("simulate", out=tmp_path, duration=0.2, tank__cells=[48, 96], output__pictures=False,
                                output__vtk=False, stability__max_speed=1e-6)
    assert e.value.summary["status"] == "failed"
    assert e.value.summary["failure"] == e.value.message
