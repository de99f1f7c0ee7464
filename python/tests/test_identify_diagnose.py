"""identify and diagnose: the command's files and JSON, to the last digit."""

import json

import pytest

import pliant
from conftest import data, read_bytes, run_cli

CALIBRATION = [data("bias_sweep.csv"), data("clamped_beam.csv")]


def without_timing(report):
    return {k: v for k, v in report.items() if k not in ("seconds", "solver", "output")}


def test_identify_smoother_is_the_commands(cli_identified, tmp_path):
    """To the last digit, as the paper's procedure below: the smoother keeps its
    blocks in one buffer, so Ceres' order of them, and the result, do not depend
    on the process's heap (test_identify_does_not_depend_on_the_heap)."""
    cli_path, cli_report = cli_identified
    params, report = pliant.identify(CALIBRATION, output=tmp_path / "mine.json")
    assert read_bytes(tmp_path / "mine.json") == read_bytes(cli_path)
    assert without_timing(report) == without_timing(cli_report)
    assert report["output"] == str(tmp_path / "mine.json")
    # The shipped logs were simulated with joint 1's clearance 0.00846 rad (README's demo).
    delta1 = next(p for p in report["parameters"] if p["name"] == "joint1.backlash_rad")
    assert delta1["value"] == pytest.approx(0.00846, abs=2e-5) and delta1["sd"] > 0


def test_identify_paper_procedure_is_the_commands(tmp_path):
    stdout, _ = run_cli("identify", *CALIBRATION, "--method", "paper", "--model", "direct_cubic",
                        "-o", tmp_path / "cli.json", "--json")
    params, report = pliant.identify(CALIBRATION, method="paper", law="direct_cubic")
    params.save(tmp_path / "mine.json")
    assert read_bytes(tmp_path / "mine.json") == read_bytes(tmp_path / "cli.json")
    assert without_timing(report) == without_timing(json.loads(stdout))
    assert report["method"] == "paper" and report["law"] == "direct_cubic"


def test_identify_with_a_prior_and_bad_names(tmp_path, cli_identified):
    with pytest.raises(pliant.InputError, match="unknown compliance law 'cubic'"):
        pliant.identify(CALIBRATION, law="cubic")
    with pytest.raises(pliant.InputError, match="unknown method 'ceres'"):
        pliant.identify(CALIBRATION, method="ceres")
    with pytest.raises(pliant.InputError, match="no_such.csv"):
        pliant.identify([data("no_such.csv")])
    cli_path, _ = cli_identified
    run_cli("identify", *CALIBRATION, "--method", "paper", "--prior", cli_path, "-o",
            tmp_path / "cli.json")
    params, _ = pliant.identify(CALIBRATION, method="paper", prior=cli_path)
    params.save(tmp_path / "mine.json")
    assert read_bytes(tmp_path / "mine.json") == read_bytes(tmp_path / "cli.json")


def test_diagnose_is_the_commands_json(tmp_path):
    log = data("divot_hidden_effect.csv")
    args = ["--candidate", "deflection_coupling", "--candidate", "effort_drift"]
    stdout, _ = run_cli("diagnose", "--params", data("paper.json"), log, *args, "-o",
                        tmp_path / "report", "--json")
    cli = json.loads(stdout)
    got = pliant.diagnose(data("paper.json"), log,
                          candidates=["deflection_coupling", "effort_drift"])
    cli.pop("report")
    assert got == cli
    assert got["missing_effect"] == "deflection_coupling"
    assert got["rms_after"] < 0.5 * got["rms_before"]


def test_diagnose_writes_its_report_and_names_a_bad_effect(tmp_path):
    got = pliant.diagnose(pliant.load_parameters(data("paper.json")),
                          data("divot_hidden_effect.csv"), candidates=["effort_drift"],
                          report_dir=tmp_path / "report")
    assert got["report"] == str(tmp_path / "report" / "index.html")
    assert (tmp_path / "report" / "index.html").stat().st_size > 1000
    with pytest.raises(pliant.InputError, match="no effect named 'spring'"):
        pliant.diagnose(data("paper.json"), data("divot_hidden_effect.csv"), add=["spring"])


def test_identify_arm_dynamics_on_the_real_free_motion(tmp_path):
    """The real PSM2 bag's own inertia and friction (docs/identification.md): a
    PSM joint's 0.1–0.3 kg·m², stated to 15 %, and most of the effort beyond the
    table explained; the saved file carries them for the filter."""
    bag = data("real/crtk2022_psm2_free.csv")
    base, _ = pliant.identify([bag])
    params, report = pliant.identify_arm_dynamics(bag, base, output=tmp_path / "arm.json")
    inertia = next(e for e in report["effects"] if e["name"] == "joint_inertia")
    for p in inertia["parameters"]:
        assert 0.1 < p["value"] < 0.3 and p["sd"] < 0.15 * p["value"], p
    for before, after in zip(report["effort_rms_before_nm"], report["effort_rms_after_nm"]):
        assert after < 0.5 * before
    assert report["rows"] == 3420 and report["blocks"] >= 5
    saved = json.loads((tmp_path / "arm.json").read_text())
    assert set(saved["effects"]) == {"joint_inertia", "joint_inertia_coupling", "joint_friction"}
    with pytest.raises(pliant.InputError, match="free motion"):
        pliant.identify_arm_dynamics(data("real/jhu2017_clamped_j1.csv"), params)


def test_identify_takes_the_real_arms_one_joint_logs_as_the_command(tmp_path):
    """The real JHU 2017 files record one joint each, one row per pose: 'auto' is the
    clamp-by-clamp fit with the held friction, as `pliant identify` chooses, to the
    last digit; the joint smoother asked for says which log it cannot take."""
    real = [data("real/jhu2017_bias_j1.csv"), data("real/jhu2017_clamped_j1.csv")]
    run_cli("identify", *real, "-o", tmp_path / "cli.json")
    params, report = pliant.identify(real, output=tmp_path / "mine.json")
    assert read_bytes(tmp_path / "mine.json") == read_bytes(tmp_path / "cli.json")
    assert report["method"] == "quasi_static"
    assert "held_friction" in json.loads((tmp_path / "mine.json").read_text())["effects"]
    pliant.identify(real, held_friction=False, output=tmp_path / "paper_form.json")
    assert "held_friction" not in json.loads((tmp_path / "paper_form.json").read_text()).get(
        "effects", {})
    with pytest.raises(pliant.InputError, match="jhu2017_bias_j1.csv, .*jhu2017_clamped_j1.csv "
                                                "record one joint only"):
        pliant.identify(real, method="smoother")


def nearly(a, b):
    """JSON values equal but for floats' last digits (rel 1e-9)."""
    if isinstance(a, dict):
        return a.keys() == b.keys() and all(nearly(a[k], b[k]) for k in a)
    if isinstance(a, list):
        return len(a) == len(b) and all(nearly(x, y) for x, y in zip(a, b))
    if isinstance(a, float):
        return b == pytest.approx(a, rel=1e-9, abs=1e-15)
    return a == b


def test_identify_fits_a_named_effect_as_the_command(tmp_path):
    """effects= is --effect: the command's file and report. The effect's Ceres
    problem orders its blocks by address, so the last digits may differ between
    processes (the base smoother's do not: test_identify_smoother_is_the_commands)."""
    logs = [data("bias_sweep.csv"), data("divot_hidden_effect.csv")]
    stdout, _ = run_cli("identify", *logs, "--effect", "deflection_coupling", "-o",
                        tmp_path / "cli.json", "--json")
    params, report = pliant.identify(logs, effects=["deflection_coupling"],
                                     output=tmp_path / "mine.json")
    mine = json.loads((tmp_path / "mine.json").read_text())
    assert nearly(mine, json.loads((tmp_path / "cli.json").read_text()))
    assert nearly(without_timing(report), without_timing(json.loads(stdout)))
    assert "deflection_coupling" in mine["effects"]
    with pytest.raises(pliant.InputError, match="--effect joint_frction: not in the catalogue"):
        pliant.identify(logs, effects=["joint_frction"])


def test_diagnose_writes_the_commands_parameters(tmp_path):
    """write_params is --write-params: the coupling added and fitted on the log it
    was found on, the command's file (to the floats' last digits, as above)."""
    log = data("divot_hidden_effect.csv")
    args = ["--add", "deflection_coupling", "--candidate", "effort_drift"]
    run_cli("diagnose", "--params", data("paper.json"), log, *args, "-o", tmp_path / "report",
            "--write-params", tmp_path / "cli.json")
    got = pliant.diagnose(data("paper.json"), log, add=["deflection_coupling"],
                          candidates=["effort_drift"], write_params=tmp_path / "mine.json")
    assert got["parameters_written"] == str(tmp_path / "mine.json")
    mine = json.loads((tmp_path / "mine.json").read_text())
    assert nearly(mine, json.loads((tmp_path / "cli.json").read_text()))
    assert "deflection_coupling" in mine["effects"]
