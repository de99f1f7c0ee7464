#!/usr/bin/python3
"""Do no harm in free motion (docs/validation-unlike-defaults.md, "The real free-motion bag").

The shared dVRK 2.x bag (data/real/crtk2022_psm2_free.csv: PSM2 moving at up to 1 rad/s,
nothing touching the instrument, so the truth is the encoder) filtered without the tip_fixed
hint: with the bias torque `pliant identify` fits on the bag itself (alone, and with the arm's
dynamics `--effect joint_inertia --effect joint_inertia_coupling --effect joint_friction` fits
on its free motion), and with the paper's
parameters (data/paper.json, another arm's bias table). Prints, per parameters file, the median
and 95th percentile of the filter's tip correction and the share of rows whose correction lies
within twice its stated standard deviation (issue 26 asks for <= 0.3 mm and >= 95 %).

Usage: free_motion.py PLIANT OUT_DIR   (a few seconds)
"""
import argparse
import csv
import os
import subprocess

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
BAG = os.path.join(HERE, "..", "data", "real", "crtk2022_psm2_free.csv")
PAPER = os.path.join(HERE, "..", "data", "paper.json")


def run(*args):
    subprocess.run([str(a) for a in args], check=True, stdout=subprocess.DEVNULL,
                   stderr=subprocess.DEVNULL)


def score(filtered_csv):
    with open(filtered_csv) as f:
        rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
    correction = np.array([float(r["tip_corr_mm"]) for r in rows])
    sd = np.array([float(r["tip_corr_sd_mm"]) for r in rows])
    within = np.mean(correction <= 2.0 * sd)
    return np.median(correction), np.percentile(correction, 95), within


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("pliant")
    parser.add_argument("out_dir")
    args = parser.parse_args()
    os.makedirs(args.out_dir, exist_ok=True)
    bias = os.path.join(args.out_dir, "bag_bias.json")
    run(args.pliant, "identify", "--quiet", BAG, "-o", bias)
    arm = os.path.join(args.out_dir, "bag_arm.json")
    run(args.pliant, "identify", "--quiet", BAG, "--effect", "joint_inertia", "--effect",
        "joint_inertia_coupling", "--effect", "joint_friction", "-o", arm)
    print(f"{'parameters':<30}{'median mm':>10}{'p95 mm':>9}{'within 2 sd':>13}")
    for name, params in (("bias from the bag", bias), ("bias and the arm's dynamics", arm),
                         ("data/paper.json", PAPER)):
        out = os.path.join(args.out_dir, "bag_filter.csv")
        run(args.pliant, "filter", "--params", params, BAG, "-o", out)
        median, p95, within = score(out)
        print(f"{name:<30}{median:>10.4f}{p95:>9.3f}{100 * within:>12.1f} %")


if __name__ == "__main__":
    main()
