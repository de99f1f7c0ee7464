#!/usr/bin/python3
"""The loop into corrected joints on the second generator's logs (docs/validation-diagnosis.md,
section 10).

For each hidden effect (generate.py's cases, the instrument options passed through), logs of seed
N (to fit) and N + 1 (unseen): `pliant identify` seed N's calibration log (which holds the effect)
without and with `--effect CASE`, and `pliant diagnose --add CASE --write-params` on seed N's
test log (the loop a user runs after the diagnosis names the effect). With each of the three files
`pliant filter` seed N + 1's test log (held pushes; with its tip_fixed column and without it,
online) and `pliant correct` it (equation (2) with the file's effects). Each is scored on the held
rows against the tracker reference: the RMS error per joint (mrad) and, for the filter, the share
inside its 95 % interval (the tracker's noise added to the stated σ).

Usage: effect_loop.py PLIANT OUT_DIR [--seed N] [--case NAME ...] [generate.py's options]
(about a minute per case)
"""
import argparse
import os
import subprocess
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import generate  # noqa: E402
from filter_families import TRACKER_NOISE, load, run, score, without_column  # noqa: E402


def correct_rms(corrected, reference, rows):
    return [1e3 * np.sqrt(np.mean((corrected["q%d_corr" % j][rows] - reference[j - 1][rows]) ** 2))
            for j in (1, 2)]


def scores(pliant, d, params, tag, noise_sd):
    path = lambda name: os.path.join(d, name)
    run(pliant, "filter", "--params", params, path("test.csv"), "-o", path("f_%s.csv" % tag))
    run(pliant, "filter", "--params", params, path("online.csv"), "-o", path("o_%s.csv" % tag))
    run(pliant, "correct", "--params", params, path("online.csv"), "-o", path("c_%s.csv" % tag))
    hinted, online = load(path("f_%s.csv" % tag)), load(path("o_%s.csv" % tag))
    corrected = load(path("c_%s.csv" % tag))
    held = np.isfinite(hinted["q1_ref"])
    reference = (hinted["q1_ref"], hinted["q2_ref"])
    return (score(hinted, reference, held, noise_sd), score(online, reference, held, noise_sd),
            correct_rms(corrected, reference, held))


def cell(scores):
    """'a/b mrad (x/y %)' for a filter's score pair."""
    return "%.2f/%.2f (%.0f/%.0f %%)" % (scores[0][0], scores[1][0], 100 * scores[0][1],
                                         100 * scores[1][1])


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("pliant")
    parser.add_argument("out_dir")
    parser.add_argument("--seed", type=int, default=11)
    parser.add_argument("--case", action="append", choices=generate.CASES[1:])
    args, instrument = parser.parse_known_args()
    cases = args.case or generate.CASES[1:]
    noise_scale = 1.0
    if "--noise-scale" in instrument:
        noise_scale = float(instrument[instrument.index("--noise-scale") + 1])
    for seed, name in ((args.seed, "fit"), (args.seed + 1, "unseen")):
        subprocess.run([sys.executable, os.path.join(HERE, "generate.py"),
                        os.path.join(args.out_dir, name), "--seed", str(seed)] +
                       sum((["--case", c] for c in cases), []) + instrument, check=True)
    noise_sd = TRACKER_NOISE * noise_scale
    print("| hidden effect | parameters | filter, tip_fixed given: j1/j2 mrad (in 95 %) | "
          "filter online | correct online (mrad) |")
    print("|---|---|---|---|---|")
    for case in cases:
        fit = os.path.join(args.out_dir, "fit", case)
        d = os.path.join(args.out_dir, "unseen", case)
        path = lambda name: os.path.join(d, name)
        without_column(path("test.csv"), path("online.csv"), "tip_fixed")
        calibration = os.path.join(fit, "calibration.csv")
        run(args.pliant, "identify", calibration, "-o", path("base.json"))
        run(args.pliant, "identify", calibration, "--effect", case, "-o", path("effect.json"))
        run(args.pliant, "diagnose", "--params", path("base.json"), os.path.join(fit, "test.csv"),
            "--add", case, "--write-params", path("diagnosed.json"), "-o", path("report"))
        for tag, label in (("base", "identified"), ("effect", "identified with --effect"),
                           ("diagnosed", "diagnose --add --write-params")):
            hinted, online, corrected = scores(args.pliant, d, path(tag + ".json"), tag, noise_sd)
            print("| %s | %s | %s | %s | %.2f/%.2f |" % (
                case if tag == "base" else "", label, cell(hinted), cell(online), *corrected))


if __name__ == "__main__":
    main()
