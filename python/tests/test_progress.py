"""The optional progress callbacks of Simulation.advance and run_experiment (issue 38): the same
objects as `jellysim ... --progress json`, as dicts; an exception raised in one stops the run."""
import json

import pytest

import jellysim
from conftest import CHEAP


def test_advance_reports_to_the_end(cheap_scene):
    lines = []
    s = jellysim.Simulation(cheap_scene)
    s.advance(0.1, progress=lines.append)
    assert lines, "no report"
    for line in lines:
        assert line["stage"] == "simulate"
        assert set(line) >= {"time", "duration", "fraction", "steps", "eta_seconds"}
        assert 0.0 <= line["fraction"] <= 1.0
    assert lines[-1]["fraction"] == 1.0 and lines[-1]["eta_seconds"] == 0.0
    assert lines[-1]["time"] == pytest.approx(s.time) and lines[-1]["steps"] == s.steps
    json.dumps(lines)  # plain JSON values


def test_advance_without_callback_still_works(cheap_scene):
    s = jellysim.Simulation(cheap_scene)
    s.advance(0.05, progress=None)
    assert s.frame_count == 3


def test_an_exception_in_the_callback_stops_advance(cheap_scene):
    class Stop(Exception):
        pass

    def stop(_line):
        raise Stop()

    s = jellysim.Simulation(cheap_scene)
    with pytest.raises(Stop):
        s.advance(1.0, progress=stop)
    assert s.time < 0.5  # stopped at the first report's frame
    s.advance(0.0)  # still usable


def test_run_experiment_reports_simulate_and_render(tmp_path):
    lines = []
    overrides = dict(CHEAP, **{"render.width": 64, "render.height": 64, "render.video": False, "duration": 0.1})
    summary = jellysim.run_experiment("run", out=tmp_path / "run", overrides=overrides, progress=lines.append)
    assert summary["status"] == "ok"
    stages = {line["stage"] for line in lines}
    assert stages == {"simulate", "render"}, stages
    render = [line for line in lines if line["stage"] == "render"]
    assert render[-1]["fraction"] == 1.0 and render[-1]["frames"] == render[-1]["frames_total"] > 0


def test_an_exception_in_run_experiment_callback_is_raised(tmp_path):
    def stop(_line):
        raise KeyError("stop")

    with pytest.raises(KeyError):
        jellysim.run_experiment("simulate", out=tmp_path / "sim", progress=stop,
                                overrides=dict(CHEAP, **{"duration": 2.0}))
    summary = json.loads((tmp_path / "sim" / "summary.json").read_text())
    assert summary["status"] == "interrupted"
    # the next run is not stopped by the first one's request
    jellysim.run_experiment("simulate", out=tmp_path / "again", overrides=dict(CHEAP, **{"duration": 0.05}))
