"""Logs as numpy columns: the values the C++ reader reads, written back bit-exact."""

import csv
import math

import numpy as np
import pytest

import pliant
from conftest import data, read_bytes, run_cli


def parse_text(path):
    """(metadata, header, rows of strings) by Python's csv module alone."""
    with open(path, newline="") as f:
        lines = f.read().splitlines()
    metadata = [line[2:].split(": ", 1) for line in lines if line.startswith("# ")]
    body = list(csv.reader(line for line in lines if not line.startswith("#")))
    return metadata, body[0], body[1:]


def test_read_log_gives_every_value_of_the_file():
    log = pliant.read_log(data("divot_push.csv"))
    metadata, header, rows = parse_text(data("divot_push.csv"))
    assert list(log) == header
    assert log.rows == len(rows) == 12313
    assert [list(pair) for pair in log.metadata] == metadata
    for c, name in enumerate(header):
        expected = np.array([float(r[c]) if r[c] else math.nan for r in rows])
        np.testing.assert_array_equal(log[name], expected)  # bit-exact, NaN where empty
        assert log[name].dtype == np.float64 and log[name].flags.c_contiguous


def test_write_log_round_trip_is_byte_identical(tmp_path):
    log = pliant.read_log(data("divot_push.csv"))
    out = tmp_path / "copy.csv"
    pliant.write_log(out, log)
    assert read_bytes(out) == read_bytes(data("divot_push.csv"))


def test_write_log_from_a_plain_dict(tmp_path):
    out = tmp_path / "small.csv"
    pliant.write_log(out, {"t": [0.0, 0.001], "q1": [0.1, 0.2], "q2": [0, 0], "q3": [0.1, 0.1],
                           "tau1": [0.25, -1e-300], "tau2": np.array([1.0, 2.0])},
                     metadata=[("note", "two rows")])
    assert out.read_text() == ("# note: two rows\nt,q1,q2,q3,tau1,tau2\n0,0.1,0,0.1,0.25,1\n"
                               "0.001,0.2,0,0.1,-1e-300,2\n")
    back = pliant.read_log(out)
    assert back["tau1"][1] == -1e-300 and back.metadata == [("note", "two rows")]


def test_a_bad_log_raises_the_commands_message(tmp_path):
    bad = tmp_path / "bad.csv"
    bad.write_text("t,q1,q2,q3,tau1,tau2\n0,0.1,0.2,120,0.3,0.4\n")
    _, stderr = run_cli("correct", "--params", data("paper.json"), bad, "-o", tmp_path / "o.csv",
                        expect=2)
    with pytest.raises(pliant.InputError) as caught:
        pliant.read_log(bad)
    assert isinstance(caught.value, ValueError)
    assert str(caught.value) == stderr.strip()
    assert (caught.value.file, caught.value.line, caught.value.column) == (str(bad), 2, 4)
    assert caught.value.problem == "q3 = 120 m is outside 0–0.3 m"
    assert caught.value.fix.startswith("this looks like millimetres")


def test_columns_of_different_lengths_write_nothing(tmp_path):
    out = tmp_path / "never.csv"
    with pytest.raises(pliant.InputError, match="column 'q1' holds 1 values"):
        pliant.write_log(out, {"t": [0.0, 1.0], "q1": [0.0]})
    assert not out.exists()
