#!/usr/bin/python3
"""The loop ends in corrected joints, effect by effect (docs/validation-diagnosis.md section 10).

For each catalogue effect (the hidden effects of tests/diagnostics/diagnosis_test.cpp's
Catalogue cases, at the same sizes), simulate the instrument with it hidden: the bias sweep
(seed 1) and the divot pushes (seed 2) to identify from, and a divot at another depth
(seed 5, 0.13 m) that neither identification sees. Then `pliant identify` the sweep and the
pushes without and with `--effect NAME`, and `pliant filter` and `pliant correct` the unseen
log with each file. Prints, per effect, the tip error each command's summary reports against
the simulated truth and the RMS error of each joint on its loaded rows (effort more than
0.3 N·m from its median), without -> with the effect.

Usage: effect_loop.py PLIANT OUT_DIR [--case NAME ...]   (about a minute per effect)
"""
import argparse
import os
import subprocess

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
SCENARIOS = os.path.join(HERE, "scenarios")

CASES = [
    ("joint_friction", '{"coulomb1":0.05,"coulomb2":0.05}', []),
    ("effort_drift", '{"rate1":0.0025,"rate2":-0.0025,"settling_rate":0.05}', []),
    ("bias_torque_depth", '{"slope1":0.8,"slope2":-0.8}', []),
    ("load_dependent_compliance", '{"gamma1":0.07,"gamma2":0.11}', []),
    ("deflection_coupling", '{"k12":0.004,"k21":-0.004}', []),
    ("backlash_depth", '{"growth1":0.05,"growth2":0.05}', []),
    ("bias_torque_cross_joint", '{"cross1":0.15,"cross2":0.15}', []),
    # The simulator delays its effort samples (a sensor, not a catalogue effect).
    ("effort_delay", None, ["sensors.effort_delay_s=0.04"]),
]


def run(*args):
    done = subprocess.run([str(a) for a in args], capture_output=True, text=True)
    if done.returncode != 0:
        raise RuntimeError("%s: %s" % (" ".join(map(str, args[:3])), done.stderr.strip()[-300:]))
    return done.stdout + done.stderr


def summary_rms_mm(output, word):
    for line in output.splitlines():
        words = line.split()
        if words and words[0] == word and "RMS" in words:
            return float(words[words.index("RMS") + 1])
    return float("nan")


def loaded_rms_mrad(path):
    rows = [line for line in open(path) if not line.startswith("#")]
    header = rows[0].strip().split(",")
    values = np.genfromtxt(rows[1:], delimiter=",", dtype=float)
    column = {name: values[:, i] for i, name in enumerate(header)}
    out = []
    for j in (1, 2):
        tau = column["tau%d" % j]
        loaded = np.abs(tau - np.median(tau)) > 0.3
        error = column["q%d_corr" % j][loaded] - column["q%d_true" % j][loaded]
        out.append(1e3 * np.sqrt(np.mean(error ** 2)))
    return out


def case(pliant, directory, name, parameters, sensors):
    os.makedirs(directory, exist_ok=True)
    path = lambda f: os.path.join(directory, f)
    hidden = "{}" if parameters is None else '{"%s":%s}' % (name, parameters)
    sets = ["--set", "hidden_effects=" + hidden]
    for s in sensors:
        sets += ["--set", s]
    divot = os.path.join(SCENARIOS, "divot.json")
    run(pliant, "simulate", os.path.join(SCENARIOS, "bias_sweep.json"), "-o", path("sweep.csv"),
        "--seed", 1, *sets)
    run(pliant, "simulate", divot, "-o", path("pushes.csv"), "--seed", 2,
        "--set", "log.every_n_periods=30", *sets)
    run(pliant, "simulate", divot, "-o", path("unseen.csv"), "--seed", 5,
        "--set", "log.every_n_periods=30", "--set", "experiment.depths_m=[0.13]", *sets)
    run(pliant, "identify", path("sweep.csv"), path("pushes.csv"), "-o", path("base.json"))
    run(pliant, "identify", path("sweep.csv"), path("pushes.csv"), "--effect", name,
        "-o", path("with.json"))
    result = {}
    for params in ("base", "with"):
        for command, word in (("filter", "filter"), ("correct", "corrected")):
            out = path("%s_%s.csv" % (command, params))
            text = run(pliant, command, "--params", path(params + ".json"), path("unseen.csv"),
                       "-o", out)
            result[command, params] = (summary_rms_mm(text, word), loaded_rms_mrad(out))
    return result


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("pliant")
    parser.add_argument("out_dir")
    parser.add_argument("--case", action="append", help="only these effects")
    args = parser.parse_args()
    print("| hidden effect | filter tip (mm) | filter loaded j1 / j2 (mrad) | "
          "correct tip (mm) | correct loaded j1 / j2 (mrad) |")
    print("|---|---|---|---|---|")
    for name, parameters, sensors in CASES:
        if args.case and name not in args.case:
            continue
        try:
            r = case(args.pliant, os.path.join(args.out_dir, name), name, parameters, sensors)
        except RuntimeError as error:
            print("| %s | failed: %s | | | |" % (name, error))
            continue
        cells = []
        for command in ("filter", "correct"):
            (tip0, (a0, b0)), (tip1, (a1, b1)) = r[command, "base"], r[command, "with"]
            cells += ["%.3f -> %.3f" % (tip0, tip1),
                      "%.2f -> %.2f / %.2f -> %.2f" % (a0, a1, b0, b1)]
        print("| %s | %s |" % (name, " | ".join(cells)), flush=True)


if __name__ == "__main__":
    main()
