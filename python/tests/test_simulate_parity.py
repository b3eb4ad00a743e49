"""advance(1.0) takes exactly the steps of `jellysim simulate --duration 1`: the markers and every
metrics.csv row agree bit for bit. slices.csv and metrics.csv print the shortest text that reads
back as the same double (io::format_double), so float() of a cell is the double simulate held."""
import csv

import numpy as np
import pytest

import jellysim
from conftest import CHEAP, run_cli


@pytest.fixture(scope="module")
def simulate_run(jellysim_bin, tmp_path_factory):
    out = tmp_path_factory.mktemp("simulate")
    sets = [a for key, value in CHEAP.items() for a in ("--set", f"{key}={str(value).lower()}")]
    run_cli(jellysim_bin, "simulate", "--duration", "1", "--out", str(out), "--quiet", *sets, check=True)
    return out


@pytest.fixture(scope="module")
def advanced(cheap_scene):
    sim = jellysim.Simulation(cheap_scene)
    sim.advance(1.0)
    return sim


def read_rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def last_frame_points(slices):
    """The last frame's umbrella points, then each tentacle's, as slices.csv orders them."""
    rows = read_rows(slices)
    last = max(int(float(r["frame"])) for r in rows)
    points = [(float(r["x"]), float(r["y"])) for r in rows if int(float(r["frame"])) == last]
    return np.array(points), last


def test_markers_equal_simulate_bit_for_bit(simulate_run, advanced):
    expected, last_frame = last_frame_points(simulate_run / "slices.csv")
    markers = advanced.markers()
    assert markers.shape == expected.shape
    assert markers.dtype == np.float64
    assert np.array_equal(markers, expected)  # exact: no tolerance
    assert advanced.frame_count == last_frame + 1


def test_metrics_equal_metrics_csv_bit_for_bit(simulate_run, advanced):
    rows = read_rows(simulate_run / "metrics.csv")
    metrics = advanced.metrics()
    assert list(metrics) == list(rows[0])  # the same columns in the same order
    for column, values in metrics.items():
        assert np.array_equal(values, np.array([float(r[column]) for r in rows])), column


def test_time_is_the_last_frame(advanced):
    assert advanced.time == pytest.approx(1.0, abs=1e-12)
    assert advanced.metrics()["t"][-1] == advanced.time


def test_two_halves_take_the_steps_of_one_advance(cheap_scene, advanced):
    sim = jellysim.Simulation(cheap_scene)
    sim.advance(0.5)
    sim.advance(0.5)
    assert sim.steps == advanced.steps
    assert np.array_equal(sim.markers(), advanced.markers())


def test_any_split_ends_on_the_frames_of_one_advance(cheap_scene, advanced):
    """Issue 35: advance(0) recorded a second frame at t = 0 (and lost the 1/30 s one), and
    advance(0.01) stepped to t = 0.01, off the frame clock. A total rounds to its nearest frame
    whatever the split: 0 + 0.01 + 1.0 ends on the frame at 1.0 s as advance(1.0) does."""
    sim = jellysim.Simulation(cheap_scene)
    sim.advance(0)
    assert sim.frame_count == 1 and sim.steps == 0
    sim.advance(0.01)
    assert sim.frame_count == 1 and sim.steps == 0
    sim.advance(1.0)
    assert sim.steps == advanced.steps
    assert np.array_equal(sim.metrics()["t"], advanced.metrics()["t"])
    assert np.array_equal(sim.markers(), advanced.markers())
