"""correct on arrays and logs: the numbers `pliant correct` writes, to the last digit."""

import numpy as np
import pytest

import pliant
from conftest import data, read_bytes, run_cli


@pytest.fixture(scope="module", params=["paper", "deadzone"])
def cli_corrected(request, tmp_path_factory):
    out = tmp_path_factory.mktemp("correct") / "out.csv"
    stdout, _ = run_cli("correct", "--params", data("paper.json"), "--model", request.param,
                        data("divot_push.csv"), "-o", out)
    return request.param, out, stdout


def test_arrays_match_the_command(cli_corrected):
    model, out, _ = cli_corrected
    log = pliant.read_log(data("divot_push.csv"))
    params = pliant.load_parameters(data("paper.json"))
    got = pliant.correct(params, log["q1"], log["q2"], log["q3"], log["tau1"], log["tau2"],
                         model=model)
    expected = pliant.read_log(out)
    np.testing.assert_array_equal(got["q1_corr"], expected["q1_corr"])
    np.testing.assert_array_equal(got["q2_corr"], expected["q2_corr"])
    # The correction moved the angles (by more than the clearance under load).
    assert np.max(np.abs(got["q1_corr"] - log["q1"])) > 0.008
    assert not got["depth_clamped"].any()


def test_correct_log_writes_the_commands_file(cli_corrected, tmp_path):
    model, out, stdout = cli_corrected
    mine = tmp_path / "mine.csv"
    log, summary = pliant.correct_log(data("paper.json"), data("divot_push.csv"), output=mine,
                                      model=model)
    assert read_bytes(mine) == read_bytes(out)
    assert summary["rows"] == log.rows == 12313
    assert summary["reference"] == "q*_true"
    # The command prints the same summary, rounded to 3 decimals.
    label = f"corrected ({model})"
    line = next(l for l in stdout.splitlines() if label in l)
    assert f"RMS {summary['corrected']['rms_mm']:7.3f} mm" in line
    assert f"max {summary['corrected']['max_mm']:7.3f} mm" in line


def test_correct_log_of_an_in_memory_log(cli_corrected):
    model, out, _ = cli_corrected
    log = pliant.read_log(data("divot_push.csv"))
    corrected, _ = pliant.correct_log(pliant.load_parameters(data("paper.json")), log,
                                      model=model)
    expected = pliant.read_log(out)
    assert list(corrected) == list(expected)
    for name in expected:
        np.testing.assert_array_equal(corrected[name], expected[name])


def test_equation_2_by_hand_on_one_sample():
    """Equation (2) with the paper's model at one sample below and one above tau_min."""
    params = pliant.load_parameters(data("paper.json"))
    at = params.at_depth(0.12)
    tau0 = pliant.correct(params, [0.1], [-0.2], [0.12], [0.0], [0.0])
    # The bias torque at this pose: tau_ext = tau − tau0, so tau = tau0 gives no load.
    tau1_0 = -tau0["tau1_ext"][0]
    below = pliant.correct(params, [0.1], [-0.2], [0.12], [tau1_0 + 0.01], [-tau0["tau2_ext"][0]])
    assert below["q1_corr"][0] == 0.1  # |tau_ext| < tau_min: no correction
    above = pliant.correct(params, [0.1], [-0.2], [0.12], [tau1_0 + 0.5], [-tau0["tau2_ext"][0]])
    expected = 0.1 - (at["delta1"] + at["K1"] * above["tau1_ext"][0])
    assert above["q1_corr"][0] == pytest.approx(expected, abs=1e-15)


def test_unknown_model_and_uneven_arrays_raise_input_error():
    params = pliant.load_parameters(data("paper.json"))
    with pytest.raises(pliant.InputError, match="use 'paper' .* or 'deadzone'"):
        pliant.correct(params, [0.1], [0.1], [0.1], [0.1], [0.1], model="sign")
    with pytest.raises(pliant.InputError, match="tau2: holds 2 values and q1 1"):
        pliant.correct(params, [0.1], [0.1], [0.1], [0.1], [0.1, 0.2])


def test_arrays_with_times_give_the_effects_the_commands_inputs(tmp_path):
    """A joint friction in the file reads each row's velocity: with t, v1, v2 the arrays give
    the command's numbers; without them (no memory) the friction meets no motion."""
    import json
    params_json = json.load(open(data("paper.json")))
    params_json["effects"] = {"joint_friction": {
        name: {"value": value, "sd": 0.0} for name, value in
        (("viscous1", 0.1), ("viscous2", 0.2), ("coulomb1", 0.05), ("coulomb2", 0.03),
         ("velocity_scale", 0.02))}}
    path = tmp_path / "friction.json"
    path.write_text(json.dumps(params_json))
    run_cli("correct", "--params", path, "--model", "deadzone", data("divot.csv"),
            "-o", tmp_path / "cli.csv")
    log = pliant.read_log(data("divot.csv"))
    params = pliant.load_parameters(path)
    args = (params, log["q1"], log["q2"], log["q3"], log["tau1"], log["tau2"])
    streamed = pliant.correct(*args, model="deadzone", t=log["t"], v1=log["v1"], v2=log["v2"])
    expected = pliant.read_log(tmp_path / "cli.csv")
    np.testing.assert_array_equal(streamed["q1_corr"], expected["q1_corr"])
    np.testing.assert_array_equal(streamed["q2_corr"], expected["q2_corr"])
    still = pliant.correct(*args, model="deadzone")
    assert np.max(np.abs(still["tau1_ext"] - streamed["tau1_ext"])) > 0.01


def test_tare_is_the_commands_on_a_real_arm(tmp_path):
    """tare='auto' is --tare auto (docs/real-data.md): the real PSM2 bag with another
    arm's bias table, tared on its steadiest unloaded run; the same file byte for
    byte from correct_log and filter_log, the summary's tare lines the command's."""
    params, bag = data("paper.json"), data("real/crtk2022_psm2_free.csv")
    for command, function in (("correct", pliant.correct_log), ("filter", pliant.filter_log)):
        stdout, _ = run_cli(command, "--params", params, bag, "--tare", "auto", "-o",
                            tmp_path / f"{command}_cli.csv")
        _, summary = function(params, bag, output=tmp_path / f"{command}_mine.csv", tare="auto")
        assert read_bytes(tmp_path / f"{command}_mine.csv") == read_bytes(
            tmp_path / f"{command}_cli.csv")
        assert summary["tare"].startswith("  tare joint 1: ") and summary["tare"] in stdout
        _, untared = function(params, bag)
        assert untared["tare"] == ""
    with pytest.raises(pliant.InputError, match="tare"):
        pliant.correct_log(params, bag, tare="sometimes")
