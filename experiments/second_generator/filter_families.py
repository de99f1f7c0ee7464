#!/usr/bin/python3
"""The filter on families of second-generator logs unlike pliant's defaults.

For each instrument variant (generate.py's options) and the control case
(no hidden effect): `pliant identify` on the calibration log, then
`pliant filter` with those parameters on
  - the calibration log (its clamps hold the tip at 0 rad: the truth),
  - the test log (held pushes at 100 Hz, or the variant's rate; scored
    against the tracker reference, whose own noise is added to the stated σ),
  - the test log without its tip_fixed column (online: nobody says the tip is
    held), beside `pliant correct` (equation (2)) on the same log,
  - the calibration log without its tip_fixed column (one row per pose, t a
    pose index), beside `pliant correct`: the clamps' error, and how far each
    moves the free rows (nothing touches the tip there).
Prints one line per variant: held-row RMS error (mrad) and the share inside
the 95 % interval per joint, the rows the filter rejected, and without the
hint the tip error (mm) each command's summary prints against the reference.

Usage: filter_families.py PLIANT OUT_DIR [--seed N]   (about 2 minutes)
"""
import argparse
import os
import subprocess

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
TRACKER_NOISE = 3e-4  # rad, generate.py's, times --noise-scale

VARIANTS = [
    ("defaults", []),
    ("K x0.7/x1.3, delta 3/12 mrad", ["--k-scale", "0.7", "1.3", "--clearance", "0.003", "0.012"]),
    ("K x1.3/x0.7, delta 12/3 mrad", ["--k-scale", "1.3", "0.7", "--clearance", "0.012", "0.003"]),
    ("take-up 0.01 N.m", ["--take-up", "0.01"]),
    ("take-up 0.15 N.m", ["--take-up", "0.15"]),
    ("noise x0.3", ["--noise-scale", "0.3"]),
    ("noise x3", ["--noise-scale", "3"]),
    ("test log at 1500 Hz", ["--rate", "1500"]),
]


def load(path):
    rows = [line for line in open(path) if not line.startswith("#")]
    header = rows[0].strip().split(",")
    values = np.genfromtxt(rows[1:], delimiter=",", dtype=float)
    return {name: values[:, i] for i, name in enumerate(header)}


def run(*args):
    subprocess.run(args, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)


def tip_rms_mm(*args):
    """Runs a `pliant filter` or `pliant correct` and returns the tip error its summary
    prints against the log's q*_ref (the corrected line: `filter` or `corrected (...)`)."""
    out = subprocess.run(args, check=True, capture_output=True, text=True)
    for line in (out.stdout + out.stderr).splitlines():
        words = line.split()
        if words and words[0] in ("filter", "corrected") and "RMS" in words:
            return float(words[words.index("RMS") + 1])
    return float("nan")


def without_column(source, target, column):
    with open(source) as f, open(target, "w") as out:
        keep = None
        for line in f:
            if line.startswith("#"):
                out.write(line)
                continue
            fields = line.rstrip("\n").split(",")
            if keep is None:
                keep = [i for i, name in enumerate(fields) if name != column]
            out.write(",".join(fields[i] for i in keep) + "\n")


def score(estimate, truth, rows, extra_sd=0.0):
    """RMS error (mrad) and share within 1.96 σ per joint, on `rows`."""
    out = []
    for j in (1, 2):
        error = estimate["q%d_corr" % j][rows] - truth[j - 1][rows]
        sd = np.sqrt(estimate["q%d_sd" % j][rows] ** 2 + extra_sd ** 2)
        out.append((1e3 * np.sqrt(np.mean(error ** 2)), np.mean(np.abs(error) <= 1.96 * sd)))
    return out


def variant(pliant, directory, seed, options):
    noise_scale = 1.0
    if "--noise-scale" in options:
        noise_scale = float(options[options.index("--noise-scale") + 1])
    run("/usr/bin/python3", os.path.join(HERE, "generate.py"), directory, "--seed", str(seed),
        "--case", "none", *options)
    d = os.path.join(directory, "none")
    path = lambda name: os.path.join(d, name)
    run(pliant, "identify", path("calibration.csv"), "-o", path("p.json"))
    run(pliant, "filter", "--params", path("p.json"), path("calibration.csv"), "-o", path("cf.csv"))
    run(pliant, "filter", "--params", path("p.json"), path("test.csv"), "-o", path("tf.csv"))
    without_column(path("test.csv"), path("online.csv"), "tip_fixed")
    tip_mm = (tip_rms_mm(pliant, "filter", "--params", path("p.json"), path("online.csv"), "-o",
                         path("of.csv")),
              tip_rms_mm(pliant, "correct", "--params", path("p.json"), path("online.csv"), "-o",
                         path("oc.csv")))
    # The calibration's clamps without the hint: one row per pose, t a pose
    # index (no "# timing" line: the filter reads the spacing).
    without_column(path("calibration.csv"), path("cal_online.csv"), "tip_fixed")
    run(pliant, "filter", "--params", path("p.json"), path("cal_online.csv"), "-o", path("cof.csv"))
    run(pliant, "correct", "--params", path("p.json"), path("cal_online.csv"), "-o", path("coc.csv"))
    cal, test = load(path("cf.csv")), load(path("tf.csv"))
    held = cal["tip_fixed"] > 0
    zero = np.zeros_like(cal["q1"])
    held_test = np.isfinite(test["q1_ref"])
    reference = (test["q1_ref"], test["q2_ref"])
    online, corrected = load(path("of.csv")), load(path("oc.csv"))
    cal_online, cal_corrected = load(path("cof.csv")), load(path("coc.csv"))
    free = ~held
    moved = lambda e: [1e3 * np.sqrt(np.mean((e["q%d_corr" % j][free] - e["q%d" % j][free]) ** 2))
                       for j in (1, 2)]
    unhinted = (score(cal_online, (zero, zero), held),
                [1e3 * np.sqrt(np.mean(cal_corrected["q%d_corr" % j][held] ** 2)) for j in (1, 2)],
                moved(cal_online), moved(cal_corrected))
    return (score(cal, (zero, zero), held),
            score(test, reference, held_test, TRACKER_NOISE * noise_scale),
            score(online, reference, held_test, TRACKER_NOISE * noise_scale),
            int(np.sum(test["flags"].astype(int) & 1)),
            [1e3 * np.sqrt(np.mean((corrected["q%d_corr" % j][held_test] -
                                    reference[j - 1][held_test]) ** 2)) for j in (1, 2)],
            unhinted, tip_mm)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("pliant")
    parser.add_argument("out_dir")
    parser.add_argument("--seed", type=int, default=5)
    args = parser.parse_args()
    print("%-30s %-27s %-27s %-27s %-13s %-9s %s" % (
        "variant", "calibration clamps", "test, tip_fixed given", "test, no tip_fixed",
        "correct", "rejected", "no tip_fixed, tip mm"))
    print("%-30s %-27s %-27s %-27s %-13s %-9s %s" % ("", "RMS mrad / in 95 %", "RMS mrad / in 95 %",
                                                   "RMS mrad / in 95 %", "RMS mrad", "",
                                                   "filter / correct"))
    unhinted = []
    for index, (name, options) in enumerate(VARIANTS):
        cal, test, online, rejected, correct, calibration_online, tip_mm = variant(
            args.pliant, os.path.join(args.out_dir, "variant%d" % index), args.seed, options)
        print("%-30s %-27s %-27s %-27s %-13s %-9d %.2f / %.2f" % (
            name, cell(cal), cell(test), cell(online), "%.2f/%.2f" % tuple(correct), rejected,
            tip_mm[0], tip_mm[1]))
        unhinted.append((name, calibration_online))
    print()
    print("%-30s %-27s %-13s %-13s %s" % ("calibration, no tip_fixed", "filter on the clamps",
                                          "correct", "free rows moved (mrad RMS)", ""))
    print("%-30s %-27s %-13s %-13s %s" % ("", "RMS mrad / in 95 %", "RMS mrad", "filter",
                                          "correct"))
    for name, (filtered, corrected, moved_filter, moved_correct) in unhinted:
        print("%-30s %-27s %-13s %-13s %s" % (name, cell(filtered), "%.2f/%.2f" % tuple(corrected),
                                              "%.2f/%.2f" % tuple(moved_filter),
                                              "%.2f/%.2f" % tuple(moved_correct)))


def cell(s):
    return "%.2f/%.2f %3.0f/%3.0f %%" % (s[0][0], s[1][0], 100 * s[0][1], 100 * s[1][1])


if __name__ == "__main__":
    main()
