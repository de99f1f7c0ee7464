#!/usr/bin/python3
"""Isolate why pliant filter's held-tip coverage drops on the third generator's logs.

With the TRUE parameters (evaluate.truth_params) and the tip_fixed hint, the filter is run on
test logs that differ in one physical effect at a time (coloured vs white effort noise, joint 1's
bias with or without its q2 dependence) and with filter options that widen its noise model.

Usage: probe.py [--pliant build/cli/pliant] [--work /tmp/third/probe]
"""
import argparse
import json
import os
import subprocess
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import evaluate as ev  # noqa: E402

LOGS = [  # name: generator arguments
    ("soft_k", ["--k-scale", "0.7", "1.35", "--clearance", "0.003", "0.011"]),
    ("soft_k_white", ["--k-scale", "0.7", "1.35", "--clearance", "0.003", "0.011", "--effort-tc", "0.0005"]),
    ("soft_k_white_nocross", ["--k-scale", "0.7", "1.35", "--clearance", "0.003", "0.011", "--effort-tc", "0.0005",
                              "--no-cross-bias"]),
    ("rate1000", ["--rate", "1000"]),
    ("rate1000_white", ["--rate", "1000", "--effort-tc", "0.0005"]),
    ("rate1000_white_nocross", ["--rate", "1000", "--effort-tc", "0.0005", "--no-cross-bias"]),
]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--pliant", default=os.path.join(HERE, "..", "..", "build", "cli", "pliant"))
    ap.add_argument("--work", default="/tmp/third/probe")
    a = ap.parse_args()
    pl = os.path.abspath(a.pliant)
    print("filter --params TRUE.json test.csv (tip_fixed hint); joint 1/joint 2: RMS and coverage of 1.96 sd on held rows"
          " and on held rows past the take-up (wall); rows flagged model mismatch")
    for name, gen in LOGS:
        wd = os.path.join(a.work, name)
        os.makedirs(wd, exist_ok=True)
        subprocess.run([sys.executable, os.path.join(HERE, "generate.py"), "--out", wd] + gen, check=True,
                       capture_output=True)
        truth = json.load(open(os.path.join(wd, "truth.json")))
        ev.truth_params(truth, os.path.join(wd, "TRUE.json"))
        orig, tr = ev.read_csv(os.path.join(wd, "test.csv")), ev.read_csv(os.path.join(wd, "test_truth.csv"))
        sig = max(truth["effort_sigma"])
        for opts in ([], ["--effort-noise-from-log"], ["--effort-noise", f"{sig:.4f}"],
                     ["--effort-noise", f"{sig:.4f}", "--effort-offset-sd", "nan"]):
            out = os.path.join(wd, "probe_out.csv")
            p = subprocess.run([pl, "filter", "--params", "TRUE.json", "test.csv", "-o", out] + opts, cwd=wd,
                               capture_output=True, text=True)
            if p.returncode:
                print(f"  {name:24s} {' '.join(opts):40s} EXIT {p.returncode}: {p.stderr.strip()[:200]}")
                continue
            m = ev.metrics(ev.read_csv(out), orig, tr, truth["full_load"])
            fl = [ln for ln in (p.stderr + p.stdout).splitlines() if "rows flagged" in ln][0].replace(",", "").split()
            print(f"  {name:24s} {' '.join(opts):40s} held {m[1]['held']:5.2f}/{m[2]['held']:5.2f} cov "
                  f"{m[1]['cov']:5.1f}/{m[2]['cov']:5.1f}%  wall {m[1]['wall']:5.2f}/{m[2]['wall']:5.2f} cov "
                  f"{m[1]['cov_wall']:5.1f}/{m[2]['cov_wall']:5.1f}%  mismatch {fl[fl.index('mismatch') + 1]}")


if __name__ == "__main__":
    main()
