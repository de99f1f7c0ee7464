#!/usr/bin/python3
"""Where the online filter loses to equation (2): error and coverage by time since each push began.

Simulates the divot scenario's eight pushes at one depth with a light, fast, noisy push (the
1.5 kHz online family's worst bins: docs/validation-unlike-defaults.md, "still short"), removes
the tip_fixed column, runs `pliant filter` (online: contact inferred) and `pliant correct`
(equation (2)) with the true parameters (data/paper.json), and prints per joint, in bins of time
since the push's segment began: the deflection (encoder minus true tip), the filter's RMS error,
the share of rows inside its 95 % interval, its median σ, equation (2)'s RMS error and the median
contact probability.

Usage: online_onset.py PLIANT OUT_DIR [--seed N] [--peak NM] [--speed RAD_S] [--noise NM]
                       [--every-n-periods N] [--params FILE]
(a few seconds)
"""
import argparse
import os
import subprocess
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)
sys.path.insert(0, os.path.join(HERE, "second_generator"))
from filter_families import load, without_column  # noqa: E402

BINS_S = [0.0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.8, 1.0, 1.5, 3.0]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("pliant")
    parser.add_argument("out_dir")
    parser.add_argument("--seed", type=int, default=7)
    parser.add_argument("--peak", type=float, default=0.35)
    parser.add_argument("--speed", type=float, default=0.045)
    parser.add_argument("--noise", type=float, default=0.025)
    parser.add_argument("--every-n-periods", type=int, default=1,
                        help="log every Nth 1.5 kHz period (15: 100 Hz, the 100 Hz family's rate)")
    parser.add_argument("--params", default=os.path.join(REPO, "data", "paper.json"),
                        help="parameters for both commands (default: the true ones, data/paper.json)")
    args = parser.parse_args()
    os.makedirs(args.out_dir, exist_ok=True)
    path = lambda name: os.path.join(args.out_dir, name)
    params = args.params
    sets = ["hidden_effects={}", "experiment.hold_s=0.5", "experiment.rest_s=0.2",
            "experiment.depths_m=[0.15]", "experiment.peak_torques_nm=[%g]" % args.peak,
            "experiment.speeds_rad_s=[%g]" % args.speed,
            "sensors.effort_noise_sd_nm=%g" % args.noise,
            "log.every_n_periods=%d" % args.every_n_periods]
    subprocess.run([args.pliant, "simulate", os.path.join(HERE, "scenarios", "divot.json"), "-o",
                    path("log.csv"), "--seed", str(args.seed)] + sum((["--set", s] for s in sets), []),
                   check=True, capture_output=True)
    without_column(path("log.csv"), path("online.csv"), "tip_fixed")
    effort = "--effort-noise=%g" % args.noise
    for command, out in (("filter", "f.csv"), ("correct", "c.csv")):
        extra = [effort] if command == "filter" else []
        subprocess.run([args.pliant, command, "--params", params, path("online.csv"), "-o",
                        path(out)] + extra, check=True, capture_output=True)
    log, filtered, corrected = load(path("log.csv")), load(path("f.csv")), load(path("c.csv"))
    segment, t = log["segment"], log["t"]
    since = np.zeros_like(t)
    starts = [0] + [i for i in range(1, len(t)) if segment[i] != segment[i - 1]] + [len(t)]
    for a, b in zip(starts[:-1], starts[1:]):
        since[a:b] = t[a:b] - t[a]
    held = log["tip_fixed"] > 0
    for j in (1, 2):
        truth = log["q%d_true" % j]
        error = filtered["q%d_corr" % j] - truth
        sd = filtered["q%d_sd" % j]
        print("joint %d  since the push began: deflection | filter RMS, in 95 %%, median sd | "
              "equation (2) RMS (mrad) | contact probability" % j)
        for a, b in zip(BINS_S[:-1], BINS_S[1:]):
            m = held & (since >= a) & (since < b)
            if not m.any():
                continue
            rms = lambda e: 1e3 * np.sqrt(np.mean(e[m] ** 2))
            print("  %.1f-%.1f s  %6.2f | %6.2f %4.0f %% %5.2f | %6.2f | %.2f" % (
                a, b, rms(log["q%d" % j] - truth), rms(error),
                100 * np.mean(np.abs(error[m]) <= 1.96 * sd[m]), 1e3 * np.median(sd[m]),
                rms(corrected["q%d_corr" % j] - truth), np.median(filtered["contact_probability"][m])))


if __name__ == "__main__":
    main()
