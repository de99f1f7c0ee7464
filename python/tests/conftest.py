"""Shared fixtures: the shipped data, the pliant command, and its outputs.

ctest runs these with PLIANT_CLI, PLIANT_SOURCE_DIR and PLIANT_BINARY_DIR set
and the build's python/ folder on PYTHONPATH (python/CMakeLists.txt).
"""

import json
import os
import subprocess

import pytest

SOURCE_DIR = os.environ.get("PLIANT_SOURCE_DIR",
                            os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..")))
CLI = os.environ.get("PLIANT_CLI", os.path.join(SOURCE_DIR, "build", "cli", "pliant"))


def data(name):
    """A shipped file in data/."""
    return os.path.join(SOURCE_DIR, "data", name)


def run_cli(*args, expect=0):
    """Runs `pliant ARGS`; returns (stdout, stderr) after checking the exit status (unless None)."""
    done = subprocess.run([CLI, *map(str, args)], capture_output=True, text=True, check=False)
    assert expect is None or done.returncode == expect, done.stderr
    return done.stdout, done.stderr


def read_bytes(path):
    with open(path, "rb") as f:
        return f.read()


@pytest.fixture(scope="session")
def cli_identified(tmp_path_factory):
    """`pliant identify --json` (smoother) on the shipped calibration logs: (path, report)."""
    out = tmp_path_factory.mktemp("cli") / "identified.json"
    stdout, _ = run_cli("identify", data("bias_sweep.csv"), data("clamped_beam.csv"), "-o", out,
                        "--json")
    return out, json.loads(stdout)
