#!/usr/bin/python3
"""Where the filter's instrument states move: steps pliant.Filter over a log and prints, at the
end of each segment, the clearance error e (mrad: the clearance is the file's δ + e) and the
compliance scale s of each joint, with the segment's depth and peak efforts. A state that walks
one way push after push is taught by a misfit the filter counts as white noise
(docs/validation-diagnosis.md, the stiffening loop).

Usage: clearance_drift.py PARAMS.json LOG.csv [--build build]   (needs the Python module built)
"""
import argparse
import io
import os
import sys

import numpy as np


def read_rows(path):
    lines = [line for line in open(path) if not line.startswith("#")]
    return np.genfromtxt(io.StringIO("".join(lines)), delimiter=",", names=True)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("params")
    parser.add_argument("log")
    parser.add_argument("--build", default=os.path.join(os.path.dirname(__file__), "..", "build"))
    args = parser.parse_args()
    sys.path.insert(0, os.path.join(args.build, "python"))
    import pliant  # noqa: E402 (built beside the CLI)

    rows = read_rows(args.log)
    held = rows["tip_fixed"] > 0.5 if "tip_fixed" in rows.dtype.names else np.zeros(len(rows), bool)
    segment = rows["segment"] if "segment" in rows.dtype.names else np.zeros(len(rows))
    nan = float("nan")
    f = pliant.Filter(pliant.load_parameters(args.params))
    print("segment  depth m  peak |tau| N·m   e1, e2 mrad      s1, s2")
    start = 0
    for i in range(len(rows)):
        r = rows[i]
        estimate = f.step(r["t"], r["q1"], r["q2"], r["q3"], r["tau1"], r["tau2"], nan, nan,
                          bool(held[i]))
        if i + 1 < len(rows) and segment[i + 1] == segment[i]:
            continue
        part = rows[start:i + 1]
        e, s = 1e3 * np.asarray(estimate.clearance_error_rad), np.asarray(estimate.compliance_scale)
        print("%7d  %7.3f  %5.2f / %5.2f    %+6.2f %+6.2f   %.3f %.3f" % (
            segment[i], r["q3"], np.max(np.abs(part["tau1"])), np.max(np.abs(part["tau2"])),
            e[0], e[1], s[0], s[1]))
        start = i + 1


if __name__ == "__main__":
    main()
