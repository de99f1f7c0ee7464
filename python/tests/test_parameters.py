"""Parameters: loaded, queried at a depth with ± σ, saved — as `pliant params` does."""

import json

import pytest

import pliant
from conftest import data, run_cli


@pytest.mark.parametrize("depth_m", [0.09, 0.12, 0.155, 0.22])
def test_at_depth_is_pliant_params_json(cli_identified, depth_m):
    path, _ = cli_identified
    stdout, _ = run_cli("params", path, "--depth", depth_m, "--json")
    at = pliant.load_parameters(path).at_depth(depth_m)
    assert at == json.loads(stdout)  # every key, to the last digit
    assert at["K1_sd"] > 0 and at["delta2_sd"] > 0  # the identified file has a covariance


def test_at_depth_of_the_papers_model():
    params = pliant.load_parameters(data("paper.json"))
    stdout, _ = run_cli("params", data("paper.json"), "--depth", 0.12, "--json")
    at = params.at_depth(0.12)
    assert at == json.loads(stdout)
    assert not params.has_covariance and at["K1_sd"] == 0.0
    assert at["inverse_K1"] == pytest.approx(1.0 / at["K1"], rel=1e-15)


def test_a_depth_outside_the_arm_raises_the_commands_fix():
    params = pliant.load_parameters(data("paper.json"))
    _, stderr = run_cli("params", data("paper.json"), "--depth", 120, expect=2)
    with pytest.raises(pliant.InputError) as caught:
        params.at_depth(120.0)
    assert caught.value.problem == "depth 120.000000 m is outside 0–0.3 m"
    assert caught.value.problem in stderr


def test_save_writes_the_same_file(cli_identified, tmp_path):
    path, _ = cli_identified
    params = pliant.load_parameters(path)
    params.save(tmp_path / "copy.json")
    assert (tmp_path / "copy.json").read_bytes() == path.read_bytes()
    assert params.to_dict() == json.loads(path.read_text())


def test_bad_parameters_name_their_line(tmp_path):
    bad = tmp_path / "bad.json"
    original = open(data("paper.json")).read()
    bad.write_text(original.replace('"format"', '"formt"', 1))
    _, stderr = run_cli("params", bad, "--depth", 0.12, expect=2)
    with pytest.raises(pliant.InputError) as caught:
        pliant.load_parameters(bad)
    assert str(caught.value) == stderr.strip()
    assert caught.value.line > 0
    with pytest.raises(pliant.InputError) as parsed:
        pliant.parameters_from_json(bad.read_text(), "inline.json")
    assert str(parsed.value) == stderr.strip().replace(str(bad), "inline.json")
