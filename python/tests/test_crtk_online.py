"""examples/crtk_online.py's ROS-free core: measured_js readings in, six-joint
positions out, the same numbers as `pliant filter` on the same samples."""

import sys

import numpy as np

import crtk_online
import pliant
from conftest import data, run_cli


def test_the_example_needs_no_ros_to_import():
    assert "crtk" not in sys.modules and "rclpy" not in sys.modules


def test_one_reading_in_and_out():
    jp = np.array([0.1, -0.2, 0.12, 0.3, -0.4, 0.5])
    jf = np.array([0.25, -0.05, 1.5, 0.0, 0.0, 0.0])
    sample = crtk_online.filter_sample(jp, jf, 12.5)
    np.testing.assert_array_equal(sample, [12.5, 0.1, -0.2, 0.12, 0.25, -0.05])
    f = pliant.Filter(pliant.load_parameters(data("paper.json")))
    estimate = f.step(sample)
    positions = crtk_online.corrected_positions(jp, estimate)
    assert positions[2:] == [0.12, 0.3, -0.4, 0.5] and len(positions) == 6
    assert positions[:2] == [estimate.corrected[0], estimate.corrected[1]]


def test_a_stream_of_readings_is_pliant_filter(tmp_path):
    """The divot pushes as an arm would send them (no tip_fixed, no truth), through
    the example's loop and through `pliant filter`: every corrected angle and σ equal."""
    full = pliant.read_log(data("divot_push.csv"))
    online = pliant.Log({n: full[n] for n in ("t", "q1", "q2", "q3", "tau1", "tau2")})
    pliant.write_log(tmp_path / "online.csv", online)
    run_cli("filter", "--params", data("paper.json"), tmp_path / "online.csv", "-o",
            tmp_path / "cli.csv")
    expected = pliant.read_log(tmp_path / "cli.csv")

    n = online.rows
    zeros = np.zeros(n)
    readings = ((np.array([online["q1"][k], online["q2"][k], online["q3"][k], 0.0, 0.0, 0.0]),
                 zeros[:6], np.array([online["tau1"][k], online["tau2"][k], 0, 0, 0, 0]),
                 online["t"][k]) for k in range(n))
    f = pliant.Filter(pliant.load_parameters(data("paper.json")))
    out = list(crtk_online.correct_stream(f, readings))
    positions = np.array([p for p, _, _ in out])
    sd = np.array([s for _, s, _ in out])
    np.testing.assert_array_equal(positions[:, 0], expected["q1_corr"])
    np.testing.assert_array_equal(positions[:, 1], expected["q2_corr"])
    np.testing.assert_array_equal(positions[:, 2], online["q3"])
    np.testing.assert_array_equal(sd[:, 0], expected["q1_sd"])
    np.testing.assert_array_equal(sd[:, 1], expected["q2_sd"])
    # Without a held tip the filter still moves the angles off the encoders.
    assert np.max(np.abs(positions[:, 0] - online["q1"])) > 1e-4
