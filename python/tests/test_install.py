"""The documented install: `cmake --install build --prefix ~/.local` puts the
package in the user's site-packages, where python3 finds it with no PYTHONPATH."""

import os
import subprocess
import sys

import pytest

BUILD = os.environ.get("PLIANT_BINARY_DIR")


@pytest.mark.skipif(not BUILD, reason="run by ctest, which names the build directory")
def test_install_into_a_fresh_home_imports(tmp_path):
    home = tmp_path / "home"
    prefix = home / ".local"
    subprocess.run(["cmake", "--install", BUILD, "--prefix", str(prefix), "--component", "python"],
                   check=True, capture_output=True)
    env = {"HOME": str(home), "PATH": os.environ.get("PATH", "/usr/bin:/bin")}
    script = ("import pliant; print(pliant.__file__); "
              "print(pliant.load_parameters(%r).at_depth(0.12)['K1'])"
              % os.path.join(os.environ["PLIANT_SOURCE_DIR"], "data", "paper.json"))
    done = subprocess.run([sys.executable, "-c", script], env=env, capture_output=True,
                          text=True, check=True, cwd=tmp_path)
    where, k1 = done.stdout.split()
    assert where.startswith(str(prefix / "lib")) and where.endswith("pliant/__init__.py")
    assert 0.05 < float(k1) < 0.1  # the paper's K1 at 12 cm, rad/(N·m)
