#!/usr/bin/python3
"""A second generator of PSM joint 1-2 logs, written apart from pliant's models.

pliant's own hidden-effect logs come from its simulator, which shares the
model that `pliant diagnose` fits. This script makes logs with its own
equations and conventions, so that the diagnosis is tested on data it was not
built for (docs/validation-diagnosis.md, section 10):

  - another instrument: compliance 0.85 x (joint 1) and 1.10 x (joint 2) the
    paper's equations (3)-(4); clearance delta 7.0 / 9.0 mrad taken up along
    a tanh of the load (pliant's model: a linear dead zone);
  - its own bias torque: a gravity-like sine in q2 growing with depth, a
    linear-in-depth offset on joint 1;
  - effort noise 8 mN.m per sample; encoder noise 10 urad; a tracker
    reference q*_ref with 0.3 mrad noise;
  - a calibration log of quasi-static poses, one row per pose (the mean of
    20 samples): a free-tip bias sweep and clamped load loops at 8 depths;
  - a test log at 100 Hz: the held tip pushed (ramp 1 s, hold 1.5 s, ramp
    down 1 s) in 8 directions, 2 loads, at 4 depths, one segment per push.

One hidden effect per case, in this generator's own form:
  none, deflection_coupling (k12 5, k21 4 mrad/N.m), effort_drift (linear in
  time, +0.08 / -0.06 N.m over the log), load_dependent_compliance
  (stiffening: K / (1 + 0.35 |tau|)), joint_friction (Coulomb 0.06 N.m,
  viscous 0.3 N.m.s/rad on the motor velocity), effort_delay (25 ms),
  backlash_depth (delta x (1 + 4 (L - 0.155))), bias_torque_cross_joint
  (joint 1 bias + 0.15 q2 + 0.10 q2^2).

The instrument and the sensors can be varied, to draw families of logs unlike
these defaults: --k-scale K1 K2, --clearance D1 D2 (rad), --take-up (N.m),
--noise-scale X (effort, encoder and tracker noise times X), --rate HZ (the
test log's sample rate).

Usage: generate.py OUT_DIR [--seed N] [--case NAME ...] [instrument options]
writes OUT_DIR/CASE/calibration.csv and OUT_DIR/CASE/test.csv per case.
"""
import argparse
import os

import numpy as np

CASES = ["none", "deflection_coupling", "effort_drift", "load_dependent_compliance",
         "joint_friction", "effort_delay", "backlash_depth", "bias_torque_cross_joint"]

PAPER_INVERSE_K = [[639.16, -432.35, 136.32, 3.12], [3163.17, -1969.15, 448.92, -6.00]]
K_SCALE = [0.85, 1.10]
DELTA = [0.0070, 0.0090]          # rad
TAKE_UP = 0.06                    # N.m: tanh width of the clearance take-up
EFFORT_NOISE = 0.008              # N.m per sample
ENCODER_NOISE = 1e-5              # rad
TRACKER_NOISE = 3e-4              # rad
RATE_HZ = 100.0


def compliance(joint, depth):
    c = PAPER_INVERSE_K[joint]
    return K_SCALE[joint] / (((c[0] * depth + c[1]) * depth + c[2]) * depth + c[3])


def bias(q1, q2, depth, case):
    """Effort the joints need at rest (N.m): this instrument's own shape."""
    b1 = 0.15 + 0.4 * (depth - 0.155) + 0.03 * np.sin(q1)
    b2 = -(0.5 * depth + 0.03) * np.sin(q2 + 0.05) + 0.02
    if case == "bias_torque_cross_joint":
        b1 = b1 + 0.15 * q2 + 0.10 * q2 ** 2
    return b1, b2


def deflection(tau, depth, case):
    """Motor minus tip angle (rad) for external loads tau = (tau1, tau2), arrays."""
    out = []
    for j in range(2):
        delta = DELTA[j]
        if case == "backlash_depth":
            delta = delta * (1.0 + 4.0 * (depth - 0.155))
        k = compliance(j, depth)
        if case == "load_dependent_compliance":
            k = k / (1.0 + 0.35 * np.abs(tau[j]))
        out.append(delta * np.tanh(tau[j] / TAKE_UP) + k * tau[j])
    if case == "deflection_coupling":
        out[0] = out[0] + 0.005 * tau[1]
        out[1] = out[1] + 0.004 * tau[0]
    return out


def effort_side(t, v, t_end, case):
    """Effort terms the model lacks (N.m) on the measured effort, per joint."""
    e = [np.zeros_like(t), np.zeros_like(t)]
    if case == "effort_drift":
        e[0] = e[0] + 0.08 * t / t_end
        e[1] = e[1] - 0.06 * t / t_end
    if case == "joint_friction":
        for j in range(2):
            e[j] = e[j] + 0.06 * np.tanh(v[j] / 0.002) + 0.3 * v[j]
    return e


def write(path, metadata, columns, rows):
    with open(path, "w") as f:
        for key, value in metadata:
            f.write("# %s: %s\n" % (key, value))
        f.write(",".join(columns) + "\n")
        for row in zip(*rows):
            f.write(",".join("" if np.isnan(x) else "%.10g" % x for x in row) + "\n")


def calibration(case, rng):
    """Quasi-static poses, one row per pose (mean of 20 samples)."""
    t, q1, q2, q3, tau1, tau2, fixed, segment = ([] for _ in range(8))
    clock, seg = 0.0, 0
    mean_noise = EFFORT_NOISE / np.sqrt(20.0)
    for depth in (0.10, 0.155, 0.21):     # free-tip bias sweep
        for sweep in (0, 1):
            seg += 1
            for a in np.arange(-1.0, 1.0001, 0.1) * (1.2 if sweep == 0 else 0.8):
                p1, p2 = (a, 0.0) if sweep == 0 else (0.0, a)
                b1, b2 = bias(p1, p2, depth, case)
                clock += 2.0
                t.append(clock), q1.append(p1), q2.append(p2), q3.append(depth)
                tau1.append(b1), tau2.append(b2), fixed.append(0), segment.append(seg)
    for depth in np.linspace(0.09, 0.22, 8):   # clamped load loops
        for joint in (0, 1):
            loop = np.concatenate([np.arange(0, 1.5, 0.1), np.arange(1.5, -1.5, -0.1),
                                   np.arange(-1.5, 0.0001, 0.1)])
            seg += 1
            for load in loop:
                tau = [0.0, 0.0]
                tau[joint] = load
                d = deflection(tau, depth, case)
                b1, b2 = bias(d[0], d[1], depth, case)
                clock += 2.0
                t.append(clock), q1.append(d[0]), q2.append(d[1]), q3.append(depth)
                tau1.append(b1 + tau[0]), tau2.append(b2 + tau[1])
                fixed.append(1), segment.append(seg)
    t = np.array(t)
    side = effort_side(t, [np.zeros_like(t)] * 2, 600.0, case)
    n = len(t)
    tau1 = np.array(tau1) + side[0] + rng.normal(0, mean_noise, n)
    tau2 = np.array(tau2) + side[1] + rng.normal(0, mean_noise, n)
    q1 = np.array(q1) + rng.normal(0, ENCODER_NOISE, n)
    q2 = np.array(q2) + rng.normal(0, ENCODER_NOISE, n)
    return (["t", "q1", "q2", "q3", "tau1", "tau2", "tip_fixed", "segment"],
            [t, q1, q2, np.array(q3), tau1, tau2, np.array(fixed), np.array(segment)])


def push_profile(ramp, hold):
    s = np.concatenate([np.linspace(0, 1, int(ramp * RATE_HZ), endpoint=False),
                        np.ones(int(hold * RATE_HZ)),
                        np.linspace(1, 0, int(ramp * RATE_HZ))])
    return s


def test_log(case, rng):
    """The held tip pushed at 100 Hz, one segment per push; a tracker reference."""
    parts = []
    seg = 0
    for depth in (0.10, 0.14, 0.18, 0.21):
        for direction in range(8):
            for load in (0.8, 1.2):
                seg += 1
                phi = 2 * np.pi * direction / 8 + 0.2 * rng.standard_normal()
                tip = rng.uniform(-0.3, 0.3, 2)
                s = push_profile(1.0, 1.5)
                free = np.zeros(int(0.5 * RATE_HZ))
                profile = np.concatenate([free, s])
                parts.append((depth, tip, load * np.cos(phi) * profile, load * np.sin(phi) * profile,
                              np.concatenate([np.zeros_like(free), np.ones_like(s)]), seg))
    ext1 = np.concatenate([p[2] for p in parts])
    ext2 = np.concatenate([p[3] for p in parts])
    depth = np.concatenate([np.full(len(p[2]), p[0]) for p in parts])
    tip1 = np.concatenate([np.full(len(p[2]), p[1][0]) for p in parts])
    tip2 = np.concatenate([np.full(len(p[2]), p[1][1]) for p in parts])
    fixed = np.concatenate([p[4] for p in parts])
    segment = np.concatenate([np.full(len(p[2]), p[5]) for p in parts])
    n = len(ext1)
    t = np.arange(n) / RATE_HZ
    d = deflection([ext1, ext2], depth, case)
    q1, q2 = tip1 + d[0], tip2 + d[1]
    v = [np.gradient(q1, t), np.gradient(q2, t)]
    for j, q in enumerate((q1, q2)):   # a new pose is a jump, not a velocity
        v[j][np.abs(v[j]) > 1.0] = 0.0
    b1, b2 = bias(q1, q2, depth, case)
    side = effort_side(t, v, t[-1], case)
    tau1 = b1 + ext1 + side[0]
    tau2 = b2 + ext2 + side[1]
    if case == "effort_delay":          # the effort arrives 25 ms late
        tau1 = np.interp(t - 0.025, t, tau1)
        tau2 = np.interp(t - 0.025, t, tau2)
    tau1 = tau1 + rng.normal(0, EFFORT_NOISE, n)
    tau2 = tau2 + rng.normal(0, EFFORT_NOISE, n)
    enc1 = q1 + rng.normal(0, ENCODER_NOISE, n)
    enc2 = q2 + rng.normal(0, ENCODER_NOISE, n)
    ref1 = np.where(fixed > 0, tip1 + rng.normal(0, TRACKER_NOISE, n), np.nan)
    ref2 = np.where(fixed > 0, tip2 + rng.normal(0, TRACKER_NOISE, n), np.nan)
    return (["t", "q1", "q2", "q3", "tau1", "tau2", "v1", "v2", "q1_ref", "q2_ref",
             "tip_fixed", "segment"],
            [t, enc1, enc2, depth, tau1, tau2, v[0], v[1], ref1, ref2, fixed, segment])


def main():
    global K_SCALE, DELTA, TAKE_UP, EFFORT_NOISE, ENCODER_NOISE, TRACKER_NOISE, RATE_HZ
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("out_dir")
    parser.add_argument("--seed", type=int, default=11)
    parser.add_argument("--case", action="append", choices=CASES)
    parser.add_argument("--k-scale", type=float, nargs=2, default=K_SCALE)
    parser.add_argument("--clearance", type=float, nargs=2, default=DELTA)
    parser.add_argument("--take-up", type=float, default=TAKE_UP)
    parser.add_argument("--noise-scale", type=float, default=1.0)
    parser.add_argument("--rate", type=float, default=RATE_HZ)
    args = parser.parse_args()
    K_SCALE, DELTA, TAKE_UP, RATE_HZ = list(args.k_scale), list(args.clearance), args.take_up, args.rate
    EFFORT_NOISE *= args.noise_scale
    ENCODER_NOISE *= args.noise_scale
    TRACKER_NOISE *= args.noise_scale
    instrument = "K x%.2f / x%.2f of the paper's, clearance %.1f / %.1f mrad" % (
        K_SCALE[0], K_SCALE[1], 1e3 * DELTA[0], 1e3 * DELTA[1])
    for index, case in enumerate(args.case or CASES):
        rng = np.random.default_rng(args.seed * 100 + index)
        directory = os.path.join(args.out_dir, case)
        os.makedirs(directory, exist_ok=True)
        meta = [("generator", "experiments/second_generator/generate.py (numpy), seed %d" % args.seed),
                ("instrument", instrument)]
        columns, rows = calibration(case, rng)
        write(os.path.join(directory, "calibration.csv"),
              meta + [("protocol", "quasi-static poses, one row per pose (mean of 20 samples)")],
              columns, rows)
        columns, rows = test_log(case, rng)
        write(os.path.join(directory, "test.csv"),
              meta + [("protocol", "held tip pushed at %g Hz, tracker reference" % RATE_HZ)],
              columns, rows)


if __name__ == "__main__":
    main()
