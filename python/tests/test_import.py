"""Real recordings imported in Python as `pliant import` imports them (docs/import.md)."""

import os

import pytest

import pliant
from conftest import data, read_bytes, run_cli

JHU = os.path.join("real", "jhu-2017")
CLAMPED = data(os.path.join(JHU, "hysteresis_output_joint_0_2017-7-25-20-30-58.csv"))
SWEEP = data(os.path.join(JHU, "small_range_torque_offsets_joint_1_2017-7-26-19-22-11.csv"))
BAG = data(os.path.join("real", "crtk-rosbag", "pitch_exp_traj_01_test_cropped.bag"))


@pytest.mark.parametrize("recording", [CLAMPED, SWEEP])
def test_a_jhu_file_gives_the_log_pliant_import_writes(tmp_path, recording):
    cli_log = tmp_path / "cli.csv"
    run_cli("import", recording, "-o", cli_log)
    log = pliant.import_recording(recording)
    assert log.import_format == ("jhu2017-clamped-beam" if recording == CLAMPED
                                 else "jhu2017-bias-sweep")
    assert len(log.import_evidence) == 1 and log.import_evidence[0].startswith(recording)
    ours = tmp_path / "python.csv"
    pliant.write_log(ours, log)
    assert read_bytes(ours) == read_bytes(cli_log)


def test_a_bag_gives_the_log_pliant_import_writes_or_says_why_it_cannot(tmp_path):
    cli_log = tmp_path / "cli.csv"
    _, err = run_cli("import", BAG, "-o", cli_log, expect=None)
    if not cli_log.exists():  # pliant built without ROS 1: the same message, as InputError
        with pytest.raises(pliant.InputError, match="without ROS 1 bag support"):
            pliant.import_recording(BAG)
        assert "without ROS 1 bag support" in err
        return
    log = pliant.import_recording(BAG, arm="PSM2")
    assert log.import_format == "ros1-bag" and log.rows > 1000
    ours = tmp_path / "python.csv"
    pliant.write_log(ours, log)
    assert read_bytes(ours) == read_bytes(cli_log)


def test_an_option_the_format_does_not_read_is_refused():
    with pytest.raises(pliant.InputError, match="--topic applies to ros2-csv"):
        pliant.import_recording(CLAMPED, topic="measured_js")
    with pytest.raises(pliant.InputError, match="no import format is called 'csv'"):
        pliant.import_recording(CLAMPED, format="csv")
    with pytest.raises(pliant.InputError, match="import the files of one recording together"):
        pliant.import_recording([CLAMPED, SWEEP])
