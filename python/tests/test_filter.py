"""The filter: over a whole log (`pliant filter`'s file, to the byte) and one
sample at a time (the same numbers, to the last digit)."""

import math
import os

import numpy as np
import pytest

import pliant
from conftest import data, read_bytes, run_cli

LOG = data("divot_push.csv")
PARAMS = data("paper.json")


@pytest.fixture(scope="module")
def cli_filtered(tmp_path_factory):
    out = tmp_path_factory.mktemp("filter") / "out.csv"
    stdout, _ = run_cli("filter", "--params", PARAMS, LOG, "-o", out)
    return out, stdout


def test_filter_log_writes_the_commands_file(cli_filtered, tmp_path):
    out, stdout = cli_filtered
    log, summary = pliant.filter_log(PARAMS, LOG, output=tmp_path / "mine.csv")
    assert read_bytes(tmp_path / "mine.csv") == read_bytes(out)
    assert summary["rows"] == log.rows == 12313 and not summary["smoothed"]
    assert f"mean NIS per measurement {summary['mean_nis_per_dof']:.3f}" in stdout
    assert f"rejected {summary['rejected_rows']}," in stdout
    # The filter beats equation (2)'s error on this log by far (docs/filter.md).
    assert summary["filtered"]["rms_mm"] < 0.5 * summary["uncorrected"]["rms_mm"]


def test_the_summary_says_when_the_file_does_not_fit_the_log(tmp_path):
    # The real JHU clamps with another arm's parameters: the clearance ends 8 σ
    # from the file's δ (docs/decisions/instrument-drift-advice.md).
    real = data(os.path.join("real", "jhu2017_clamped_j1.csv"))
    _, summary = pliant.filter_log(PARAMS, real, output=tmp_path / "out.csv")
    assert any(a.startswith("joint 1's clearance ended") for a in summary["advice"])
    _, shipped = pliant.filter_log(PARAMS, LOG, output=tmp_path / "shipped.csv")
    assert not any("ended" in a for a in shipped["advice"])


@pytest.mark.parametrize("flags, options", [
    (["--smooth"], {"smooth": True}),
    (["--effort-noise", "0.02", "--gate", "0.99"], {"effort_noise_nm": 0.02,
                                                    "gate_probability": 0.99}),
    (["--unloaded-start", "0.15"], {"unloaded_start_s": 0.15}),
    (["--no-load-following", "--clearance-sd", "0.002"], {"load_follows_motor": False,
                                                          "backlash_sd_rad": 0.002}),
    (["--no-contact-inference"], {"infer_contact": False}),
    (["--fixed-contact-rates"], {"learn_contact_rates": False}),
    (["--effort-noise-from-log"], {"effort_noise_from_log": True}),
    (["--effort-offset-sd", "0.01", "--effort-offset-correlation", "0.02"],
     {"effort_offset_sd_nm": 0.01, "effort_offset_correlation_s": 0.02}),
    (["--no-effort-colour"], {"effort_colour_from_log": False}),
])
def test_options_are_the_commands(tmp_path, flags, options):
    run_cli("filter", "--params", PARAMS, LOG, "-o", tmp_path / "cli.csv", *flags)
    pliant.filter_log(PARAMS, LOG, output=tmp_path / "mine.csv", **options)
    assert read_bytes(tmp_path / "mine.csv") == read_bytes(tmp_path / "cli.csv")


def samples(log):
    """(t, q1, q2, q3, tau1, tau2, q1_ref, q2_ref, tip_fixed) rows."""
    nan = np.full(log.rows, math.nan)
    columns = [log[n] for n in ("t", "q1", "q2", "q3", "tau1", "tau2")]
    columns += [log.get("q1_ref", nan), log.get("q2_ref", nan), log["tip_fixed"]]
    return np.column_stack(columns)


def test_step_by_step_is_the_commands_log(cli_filtered):
    out, _ = cli_filtered
    expected = pliant.read_log(out)
    f = pliant.Filter(pliant.load_parameters(PARAMS))
    got = {n: [] for n in ("q1_corr", "q2_corr", "q1_sd", "q2_sd", "q12_cov", "tip_corr_mm",
                           "tip_corr_sd_mm", "nis", "flags", "contact_probability")}
    for sample in samples(pliant.read_log(LOG)):
        e = f.step(sample)
        for name, value in zip(got, (e.corrected[0], e.corrected[1], e.sd[0], e.sd[1],
                                     e.covariance[0, 1], e.tip_correction_mm,
                                     e.tip_correction_sd_mm, e.nis, e.flags,
                                     e.contact_probability[0])):
            got[name].append(value)
    for name, values in got.items():
        np.testing.assert_array_equal(np.array(values, dtype=np.float64), expected[name], name)
    assert e.covariance.shape == (2, 2) and e.sd[0] == math.sqrt(e.covariance[0, 0])


def test_floats_arrays_and_reset_agree():
    rows = samples(pliant.read_log(LOG))[:500]
    f = pliant.Filter(pliant.load_parameters(PARAMS), effort_noise_nm=0.02)
    by_array = [f.step(r).corrected.copy() for r in rows]
    f.reset()
    by_floats = [f.step(*r[:6], q1_ref=r[6], q2_ref=r[7], tip_fixed=bool(r[8])).corrected.copy()
                 for r in rows]
    np.testing.assert_array_equal(by_array, by_floats)
    assert by_array[0][0] != by_array[-1][0] or by_array[0][1] != by_array[-1][1]


def test_bad_options_raise_the_commands_text(tmp_path):
    params = pliant.load_parameters(PARAMS)
    _, stderr = run_cli("filter", "--params", PARAMS, "--gate", "1.5", LOG, "-o",
                        tmp_path / "o.csv", expect=2)
    with pytest.raises(pliant.InputError) as caught:
        pliant.Filter(params, gate_probability=1.5)
    assert stderr.strip() == f"--gate: {caught.value.problem} — {caught.value.fix}"
    with pytest.raises(pliant.InputError, match="unknown option — use one of: sample_period_s"):
        pliant.Filter(params, gate=0.99)
    with pytest.raises(pliant.InputError, match="give True or False"):
        pliant.Filter(params, load_follows_motor=1)
    with pytest.raises(pliant.InputError, match="sample: holds 5 values"):
        pliant.Filter(params).step(np.zeros(5))
    assert not (tmp_path / "o.csv").exists()


def test_option_defaults_are_the_filters():
    defaults = pliant.filter_option_defaults()
    assert defaults["effort_noise_nm"] == 0.01 and defaults["gate_probability"] == 0.9999
    assert math.isnan(defaults["deflection_model_error"])
    assert list(defaults["effort_offset_sd_nm"]) == [0.0, 0.0]
