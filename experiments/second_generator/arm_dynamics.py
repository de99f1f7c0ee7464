#!/usr/bin/python3
"""The arm's dynamics identified on the second generator's free motion (arm.py).

For each seed: arm.py draws a free-motion log; `pliant identify LOG --effect
joint_inertia --effect joint_inertia_coupling --effect joint_friction --json`
fits the arm's dynamics there
(its `free_motion_fit`), and `pliant identify LOG` fits the bias table alone
(the baseline). Per seed it prints
  - J1, J2 ± σ and z = (J - J_true)/σ, and the coupling's z (M12, the mass
    matrix off its diagonal);
  - the friction judged by its torque, since arm.py's law (a Stribeck curve,
    its own sign width) is not pliant's: RMS over the log's rows of the
    identified law minus the true one, at the true velocity, as a share of
    the true friction's RMS;
  - the effort beyond the bias table, RMS before -> after the fit (the fit's
    own figures, mN.m; the white effort noise is their floor);
  - do no harm: `pliant filter` with each parameters file, without any
    tip_fixed hint; nothing touches the tip, so every correction is false:
    median and 95th percentile of tip_corr_mm and the share of rows with
    tip_corr_mm <= 2 tip_corr_sd_mm (asked: median <= 0.3 mm, >= 95 %).
Then the summary: the 2N 95 % inertia intervals that hold the truth, max |z|,
the bias and spread of J over seeds against the stated σ, the median friction
torque error, and the seeds that pass the do-no-harm bounds.

By default the same runs follow for three variants (--rate 100,
--noise-scale 3, --inertia-scale 2; --variant-seeds each); --no-variants skips
them. The arm options (arm.py --help) change the arm of every configuration.

Usage: arm_dynamics.py PLIANT OUT_DIR [--seeds N] [--first-seed S] [--variant-seeds M]
                       [--no-variants] [arm options]   (about 2.5 minutes)
"""
import argparse
import copy
import json
import os
import subprocess
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import arm  # noqa: E402

VARIANTS = [("--rate 100", {"rate": 100.0}), ("--noise-scale 3", {"noise_scale": 3.0}),
            ("--inertia-scale 2", {"inertia_scale": 2.0})]
Z95 = 1.96


def run(*args):
    """Runs a pliant command; returns its standard output (stops the study on failure)."""
    done = subprocess.run([str(a) for a in args], capture_output=True, text=True)
    if done.returncode != 0:
        sys.exit("failed (exit %d): %s\n%s" % (done.returncode, " ".join(map(str, args)), done.stderr))
    return done.stdout


def parameters(fit, effect):
    """{name: (value, sd)} of one effect of the JSON's free_motion_fit."""
    for e in fit["effects"]:
        if e["name"] == effect:
            return {p["name"]: (p["value"], p["sd"]) for p in e["parameters"]}
    raise KeyError(effect)


def friction_error_share(fit, sim):
    """Per joint: RMS of (pliant's identified friction law - the true friction),
    both at the true velocity, over the RMS of the true friction."""
    p = parameters(fit, "joint_friction")
    out = []
    for j in range(2):
        v = sim["v"][j]
        identified = (p["viscous%d" % (j + 1)][0] * v +
                      p["coulomb%d" % (j + 1)][0] * np.tanh(v / p["velocity_scale"][0]))
        true = sim["friction"][j]
        out.append(np.sqrt(np.mean((identified - true) ** 2) / np.mean(true ** 2)))
    return out


def harm(filtered_csv):
    """Median and p95 of tip_corr_mm (mm) and the share of rows within 2 tip_corr_sd_mm
    (a NaN correction counts as outside)."""
    with open(filtered_csv) as f:
        lines = [line for line in f if not line.startswith("#")]
    header = lines[0].strip().split(",")
    values = np.genfromtxt(lines[1:], delimiter=",")
    corr = values[:, header.index("tip_corr_mm")]
    sd = values[:, header.index("tip_corr_sd_mm")]
    return np.nanmedian(corr), np.nanpercentile(corr, 95), np.mean(corr <= 2.0 * sd)


def passes(h):
    return h[0] <= 0.3 and h[2] >= 0.95


def one_seed(pliant, directory, options, seed):
    """Generates, identifies (with and without the effects), filters and scores one log."""
    sim = arm.simulate(options, seed)
    stem = os.path.join(directory, "seed%02d" % seed)
    log = stem + ".csv"
    arm.write_log(log, sim)
    with_arm, table = stem + "_P.json", stem + "_B.json"
    fit = json.loads(run(pliant, "identify", "--quiet", log, "--effect", "joint_inertia",
                         "--effect", "joint_inertia_coupling", "--effect", "joint_friction",
                         "-o", with_arm, "--json"))["free_motion_fit"]
    run(pliant, "identify", "--quiet", log, "-o", table)
    scores = []
    for params, name in ((with_arm, "F"), (table, "FB")):
        out = stem + "_%s.csv" % name
        run(pliant, "filter", "--quiet", "--params", params, log, "-o", out)
        scores.append(harm(out))
    inertia = parameters(fit, "joint_inertia")
    j = [inertia["inertia1"], inertia["inertia2"]]
    z = [(j[k][0] - sim["arm"]["inertia"][k]) / j[k][1] for k in range(2)]
    m12 = parameters(fit, "joint_inertia_coupling")["inertia12"]
    z.append((m12[0] - sim["arm"]["coupling"]) / m12[1])
    return {"seed": seed, "J": j, "z": z, "friction": friction_error_share(fit, sim),
            "before": fit["effort_rms_before_nm"], "after": fit["effort_rms_after_nm"],
            "blocks": fit["blocks"], "correlation_s": fit["correlation_s"],
            "arm": scores[0], "table": scores[1]}


def report(title, options, results):
    truth = arm.truth(options)["inertia"]
    print("\n### %s: J %.3g / %.3g kg.m^2, %d seeds, white effort noise %.1f mN.m\n" % (
        title, truth[0], truth[1], len(results), 1e3 * arm.EFFORT_NOISE * options.noise_scale))
    print("| seed | J1 ± σ | z1 | J2 ± σ | z2 | friction err j1 / j2 | effort RMS before -> after "
          "j1 / j2 (mN.m) | blocks × τ | filter, arm: median / p95 mm, ≤2σ | filter, table only |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for r in results:
        print("| %d | %.4f ± %.4f | %+.2f | %.4f ± %.4f | %+.2f | %.0f %% / %.0f %% | "
              "%.0f -> %.1f / %.0f -> %.1f | %d × %.2f s | %.4f / %.4f, %.1f %% | %.4f / %.4f, %.1f %% |" % (
                  r["seed"], r["J"][0][0], r["J"][0][1], r["z"][0], r["J"][1][0], r["J"][1][1],
                  r["z"][1], 100 * r["friction"][0], 100 * r["friction"][1],
                  1e3 * r["before"][0], 1e3 * r["after"][0], 1e3 * r["before"][1], 1e3 * r["after"][1],
                  r["blocks"], r["correlation_s"], r["arm"][0], r["arm"][1], 100 * r["arm"][2],
                  r["table"][0], r["table"][1], 100 * r["table"][2]))
    z = np.array([r["z"] for r in results])
    print("\n- inertia 95 %% intervals holding the truth (J1, J2, M12): %d of %d; max |z| %.2f" % (
        np.sum(np.abs(z) <= Z95), z.size, np.max(np.abs(z))))
    for k in range(2):   # is a miss a bias (mean off) or a σ too small (spread > σ)?
        values = np.array([r["J"][k][0] for r in results])
        sds = np.array([r["J"][k][1] for r in results])
        print("- J%d: mean error %+.4f (%+.1f %%), spread over seeds %.4f, median stated σ %.4f, "
              "mean z %+.2f, sd of z %.2f" % (
                  k + 1, values.mean() - truth[k], 100 * (values.mean() / truth[k] - 1),
                  values.std(ddof=1) if len(values) > 1 else 0.0, np.median(sds),
                  z[:, k].mean(), z[:, k].std(ddof=1) if len(values) > 1 else 0.0))
    share = np.array([r["friction"] for r in results])
    print("- friction torque error, median over seeds: %.1f %% / %.1f %% (max %.1f %%)" % (
        100 * np.median(share[:, 0]), 100 * np.median(share[:, 1]), 100 * share.max()))
    for key, name in (("arm", "with the arm's dynamics"), ("table", "bias table only")):
        h = np.array([r[key] for r in results])
        print("- do no harm, %s: %d of %d seeds pass (median <= 0.3 mm, >= 95 %% within 2σ); "
              "worst median %.4f mm, worst p95 %.3f mm, worst within %.1f %%" % (
                  name, sum(passes(r[key]) for r in results), len(results), h[:, 0].max(),
                  h[:, 1].max(), 100 * h[:, 2].min()))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("pliant")
    parser.add_argument("out_dir")
    parser.add_argument("--seeds", type=int, default=10)
    parser.add_argument("--first-seed", type=int, default=1)
    parser.add_argument("--variant-seeds", type=int, default=5)
    parser.add_argument("--no-variants", action="store_true")
    arm.add_arguments(parser)
    args = parser.parse_args()
    configurations = [("base", args, args.seeds)]
    if not args.no_variants:
        for title, change in VARIANTS:
            options = copy.copy(args)
            for key, value in change.items():
                setattr(options, key, value)
            configurations.append((title, options, args.variant_seeds))
    for index, (title, options, seeds) in enumerate(configurations):
        directory = os.path.join(args.out_dir, "config%d" % index)
        os.makedirs(directory, exist_ok=True)
        results = [one_seed(args.pliant, directory, options, seed)
                   for seed in range(args.first_seed, args.first_seed + seeds)]
        report(title, options, results)


if __name__ == "__main__":
    main()
