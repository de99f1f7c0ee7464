#!/usr/bin/python3
"""Does the filter's interval hold on the real clamped beam? (docs/validation.md §3)

../shared/tools/clamped_cv.py identifies on half of the JHU 2017 clamps' depths and filters the
other half without `tip_fixed` (online). The tip is clamped, so the true angle is constant
within a depth; its median corrected angle stands in for it (127–155 rows a depth: the
median's own error is small beside the σ). Printed per log: the share of rows whose corrected
angle lies within 1.96 of its stated σ of that median, overall, on the first three poses of
each depth (the shaft starts where the last depth left it, and the bias torque was recorded on
another day) and on the rest; with the filter's default and with the bias table's doubt
(`--effort-offset-sd 0.02`; docs/decisions/effort-offset-on-real-arms.md).

Usage: real_clamp_coverage.py PLIANT OUT_DIR   (10 s; CLAMPED_CV: the path of clamped_cv.py if it
is not at ../shared/tools/)
"""
import os
import subprocess
import sys

import numpy as np

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CV = os.environ.get("CLAMPED_CV",
                    os.path.join(os.path.dirname(REPO), "shared", "tools", "clamped_cv.py"))
REAL = os.path.join(REPO, "data", "real")
FIRST_POSES = 3


def load(path):
    rows = [line for line in open(path) if not line.startswith("#")]
    header = rows[0].strip().split(",")
    values = np.array([[float(x) if x not in ("", "nan") else np.nan
                        for x in r.strip().split(",")] for r in rows[1:]])
    return {name: values[:, i] for i, name in enumerate(header)}


def coverage(log_path, filtered_path, joint):
    log, filtered = load(log_path), load(filtered_path)
    depth_bin = np.round(log["q3"] / 0.005)
    q, sd = filtered["q%d_corr" % joint], filtered["q%d_sd" % joint]
    first, rest = [], []
    for level in sorted(set(depth_bin)):
        rows = np.where(depth_bin == level)[0]
        z = np.abs(q[rows] - np.median(q[rows])) / sd[rows]
        first += list(z[:FIRST_POSES])
        rest += list(z[FIRST_POSES:])
    share = lambda z: 100.0 * np.mean(np.array(z) < 1.96)
    return len(first) + len(rest), share(first + rest), share(first), share(rest), np.median(sd)


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    pliant, work = sys.argv[1], sys.argv[2]
    os.makedirs(work, exist_ok=True)
    if not os.path.isfile(CV):
        sys.exit("%s not found: set CLAMPED_CV to the path of clamped_cv.py (docs/real-data.md)" % CV)
    logs = [os.path.join(REAL, "jhu2017_%s_j%d.csv" % (kind, j))
            for kind in ("bias", "clamped") for j in (1, 2)]
    done = subprocess.run([sys.executable, CV, pliant] + logs + ["--work", work],
                          capture_output=True, text=True)
    if done.returncode != 0:
        sys.exit(done.stderr)
    for title, flags in (("the default (the bias table taken as exact)", None),
                         ("--effort-offset-sd 0.02 (the table's doubt)", ["--effort-offset-sd", "0.02"])):
        print(title)
        print("log (held-out depths)  rows  within 1.96 σ of the depth's median: all / first %d "
              "poses / the rest   median σ" % FIRST_POSES)
        for joint in (1, 2):
            for half in (0, 1):
                name = "test_j%d_%d.csv" % (joint, half)
                path = os.path.join(work, name)
                filtered = path + ".filter.csv"
                if flags:  # the same held-out half and parameters, with the option
                    filtered = path + ".offset.csv"
                    subprocess.run([pliant, "filter", "--quiet", "--params",
                                    os.path.join(work, "params_%d.json" % half), path, "-o",
                                    filtered] + flags, check=True, capture_output=True)
                n, all_rows, first, rest, sd = coverage(path, filtered, joint)
                print("%-22s %5d  %5.1f / %5.1f / %5.1f %%   %.2f mrad" %
                      (name, n, all_rows, first, rest, 1e3 * sd))


if __name__ == "__main__":
    main()
