#!/usr/bin/python3
"""Where the filter's instrument states move: steps pliant.Filter over a log and prints, at the
end of each segment, the clearance error e (mrad: the clearance is the file's δ + e) and the
compliance scale s of each joint, with the segment's depth and peak efforts. A state that walks
one way push after push is taught by a misfit the filter counts as white noise
(docs/validation-diagnosis.md, the stiffening loop).

With --by-load it then prints how far e moved in total at each size of the filter's load
estimate, per joint: where the learning happens (in the take-up, on the wall).

--option NAME=VALUE (repeatable) sets a filter option (pliant.filter_options() lists them), e.g.
--option deadzone_width_sd_nm=0 for a take-up width known exactly (its doubt limits what the take-up
teaches e: ClearanceLearnable).

Usage: clearance_drift.py PARAMS.json LOG.csv [--by-load] [--option NAME=VALUE] [--build build]
(needs the Python module built)
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
    parser.add_argument("--by-load", action="store_true")
    parser.add_argument("--option", action="append", default=[], metavar="NAME=VALUE")
    parser.add_argument("--build", default=os.path.join(os.path.dirname(__file__), "..", "build"))
    args = parser.parse_args()
    sys.path.insert(0, os.path.join(args.build, "python"))
    import pliant  # noqa: E402 (built beside the CLI)

    rows = read_rows(args.log)
    held = rows["tip_fixed"] > 0.5 if "tip_fixed" in rows.dtype.names else np.zeros(len(rows), bool)
    segment = rows["segment"] if "segment" in rows.dtype.names else np.zeros(len(rows))
    nan = float("nan")
    options = {name: float(value) for name, value in (o.split("=", 1) for o in args.option)}
    f = pliant.Filter(pliant.load_parameters(args.params), **options)
    print("segment  depth m  peak |tau| N·m   e1, e2 mrad      s1, s2")
    start = 0
    edges = np.array([0.0, 0.1, 0.2, 0.4, 0.7, np.inf])  # N·m
    moved, last_e = np.zeros((2, len(edges) - 1)), np.zeros(2)
    for i in range(len(rows)):
        r = rows[i]
        estimate = f.step(r["t"], r["q1"], r["q2"], r["q3"], r["tau1"], r["tau2"], nan, nan,
                          bool(held[i]))
        now_e = 1e3 * np.asarray(estimate.clearance_error_rad)
        load = np.abs(np.asarray(estimate.external_torque_nm))
        for j in range(2):
            moved[j, min(np.searchsorted(edges, load[j], side="right") - 1, len(edges) - 2)] += (
                now_e[j] - last_e[j])
        last_e = now_e
        if i + 1 < len(rows) and segment[i + 1] == segment[i]:
            continue
        part = rows[start:i + 1]
        e, s = 1e3 * np.asarray(estimate.clearance_error_rad), np.asarray(estimate.compliance_scale)
        print("%7d  %7.3f  %5.2f / %5.2f    %+6.2f %+6.2f   %.3f %.3f" % (
            segment[i], r["q3"], np.max(np.abs(part["tau1"])), np.max(np.abs(part["tau2"])),
            e[0], e[1], s[0], s[1]))
        start = i + 1
    if args.by_load:
        print("\ne moved (mrad) while the filter's load estimate |tau| was in (N·m):")
        for k in range(len(edges) - 1):
            print("  %.1f-%-4s   joint 1 %+6.2f   joint 2 %+6.2f" % (
                edges[k], "" if np.isinf(edges[k + 1]) else "%.1f" % edges[k + 1],
                moved[0, k], moved[1, k]))


if __name__ == "__main__":
    main()
