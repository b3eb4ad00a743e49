"""jellysim.Simulation: stepping, the recorded frames, the grid views, metrics and meshes."""
import _thread
import threading

import numpy as np
import pytest

import jellysim
from conftest import CHEAP


@pytest.fixture(scope="module")
def sim(cheap_scene):
    s = jellysim.Simulation(cheap_scene)
    s.advance(0.1)
    return s


def test_step_lands_on_frame_times(cheap_scene):
    s = jellysim.Simulation(cheap_scene)
    assert s.time == 0.0 and s.frame_count == 1
    while s.frame_count < 2:
        s.step()
    assert s.time == pytest.approx(cheap_scene.frame_interval, abs=1e-12)


def test_frames_and_metrics(sim):
    assert sim.frame_count == 4  # t = 0 and three frames of 1/30 s
    m = sim.metrics()
    assert list(m) == ["t", "position", "velocity", "acceleration", "volume", "aperture_area", "volume_ratio",
                       "aperture_ratio", "thrust", "lateral", "daniel_velocity", "daniel_position"]
    assert all(v.shape == (4,) and v.dtype == np.float64 for v in m.values())
    assert m["t"][0] == 0.0 and m["t"][-1] == sim.time


def test_velocity_field_is_a_read_only_view(sim, cheap_scene):
    f = sim.velocity_field()
    nx, ny = 48, 96
    assert f["u"].shape == (ny, nx + 1) and f["v"].shape == (ny + 1, nx) and f["pressure"].shape == (ny, nx)
    assert f["x_faces"].shape == (nx + 1,) and f["y_faces"].shape == (ny + 1,)
    assert f["x_faces"][0] == 0.0 and f["x_faces"][-1] == pytest.approx(0.24)
    assert f["y_centres"][0] == pytest.approx(0.48 / ny / 2)
    for name in ("u", "v", "pressure"):
        assert not f[name].flags.writeable and not f[name].flags.owndata
        with pytest.raises(ValueError):
            f[name][0, 0] = 1.0
    assert np.all(np.isfinite(f["u"])) and np.abs(f["v"]).max() > 0.0


def test_view_keeps_the_simulation_alive(cheap_scene):
    s = jellysim.Simulation(cheap_scene)
    u = s.velocity_field()["u"]
    del s
    assert u.sum() == 0.0  # the water is still: the storage is alive


def test_mesh(sim):
    vertices, triangles = sim.mesh(-1)
    assert vertices.ndim == 2 and vertices.shape[1] == 3 and vertices.dtype == np.float64
    assert triangles.ndim == 2 and triangles.shape[1] == 3 and triangles.dtype == np.int64
    assert triangles.min() >= 0 and triangles.max() < len(vertices)
    first, _ = sim.mesh(0)
    assert first.shape == vertices.shape
    with pytest.raises(IndexError):
        sim.mesh(sim.frame_count)


def test_markers_are_copies(sim):
    m = sim.markers()
    assert m.ndim == 2 and m.shape[1] == 2 and m.flags.writeable
    m[:] = 0.0
    assert sim.markers().any()


def test_bad_advance(cheap_scene):
    s = jellysim.Simulation(cheap_scene)
    with pytest.raises(jellysim.InputError):
        s.advance(-1.0)


def test_gil_is_released_while_stepping(cheap_scene):
    """Python code runs in this thread while another thread is inside advance(): it sees the
    simulation busy, which it could not if advance() held the GIL."""
    s = jellysim.Simulation(cheap_scene)
    worker = threading.Thread(target=s.advance, args=(3.0,))
    saw_busy = False
    worker.start()
    while worker.is_alive():
        try:
            s.time
        except RuntimeError as e:
            assert "another thread" in str(e)
            saw_busy = True
    worker.join()
    assert saw_busy
    assert s.time == pytest.approx(3.0, abs=1e-12)


def test_ctrl_c_stops_advance_at_a_frame(cheap_scene):
    s = jellysim.Simulation(cheap_scene)
    timer = threading.Timer(0.05, _thread.interrupt_main)  # as if Ctrl-C were pressed
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        s.advance(100.0)
    timer.join()
    stopped_at = s.time
    assert 0.0 < stopped_at < 100.0
    assert s.metrics()["t"][-1] == stopped_at  # stopped on a recorded frame
    s.advance(2 * cheap_scene.frame_interval)  # goes on from there
    assert s.time == pytest.approx(stopped_at + 2 * cheap_scene.frame_interval, abs=1e-9)


def test_failed_step_raises_and_keeps_the_failing_frame():
    s = jellysim.Simulation(jellysim.load_scene(overrides={**CHEAP, "stability.max_speed": 1e-6}))
    with pytest.raises(jellysim.RunError, match="numerical instability") as e:
        s.advance(0.2)
    assert s.frame_count == 2 and s.metrics()["t"][-1] == s.time  # as simulate: the state that failed
    with pytest.raises(jellysim.RunError) as again:
        s.step()
    assert again.value.message == e.value.message
