#!/usr/bin/python3
"""Free-motion logs of an arm unlike pliant's simulator (the second generator's arm).

pliant fits the arm's own dynamics (`identify --effect joint_inertia --effect
joint_friction`) on free motion, so far only on its own simulator and one real
bag. This arm is written apart from pliant's models, in its own conventions:

  - inertia J per joint (0.12 / 0.09 kg.m^2) and an inertial cross-coupling
    C (0.01 kg.m^2) on the other joint's acceleration (a mass matrix
    [[J1, C], [C, J2]]), which pliant's joint_inertia lacks;
  - friction b.v + s(v).[Fc + (Fs - Fc).exp(-(v/vs)^2)]: viscous 0.08 / 0.15
    N.m.s/rad, Coulomb 0.07 N.m with a Stribeck bump to a static 0.10 N.m
    below vs = 0.02 rad/s, its sign s(v) = tanh(v/eps) with eps 0.005 rad/s
    (pliant's joint_friction: b.v + F.tanh(v/v_s), no bump, one width);
  - generate.bias(q1, q2, depth, "none"): the second generator's bias torque;
  - a sum of three sines per joint with random phases (peak 0.4-0.8 rad,
    periods 2-8 s, peak speed at most 1 rad/s), the insertion depth slowly
    varying in 0.10-0.20 m (or fixed: --depth);
  - effort noise 8 mN.m white (times --noise-scale), optionally plus AR(1)
    noise (--ar-sd, --ar-time); encoders 10 urad; velocities the true ones
    plus 1 mrad/s (--velocity-noise); both times --noise-scale.

Nothing touches the tip: no tip_fixed column. The log's columns are
t,q1,q2,q3,tau1,tau2,v1,v2 (docs/log-format.md), written by generate.write.

Usage: arm.py OUT.csv [--seed N] [arm options]   (arm.py --help lists them)
From Python: simulate(options, seed) returns the log's columns and the truth
(true q, v, a and each term of the effort), write_log(path, sim) writes it.
"""
import argparse
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import generate  # noqa: E402  (its bias torque and its CSV writer)

ENCODER_NOISE = 1e-5   # rad, as generate.py's
EFFORT_NOISE = 0.008   # N.m per sample, as generate.py's


def add_arguments(parser):
    """The arm's options, shared with arm_dynamics.py."""
    a = parser.add_argument
    a("--duration", type=float, default=30.0, help="s")
    a("--rate", type=float, default=1000.0, help="Hz")
    a("--inertia", type=float, nargs=2, default=[0.12, 0.09], help="J1 J2, kg.m^2")
    a("--inertia-scale", type=float, default=1.0, help="J1, J2 (not the coupling) times this")
    a("--coupling", type=float, default=0.01, help="kg.m^2 on the other joint's acceleration")
    a("--viscous", type=float, nargs=2, default=[0.08, 0.15], help="N.m.s/rad")
    a("--coulomb", type=float, default=0.07, help="N.m, both joints")
    a("--static", type=float, default=0.10, help="N.m at rest (= --coulomb: no Stribeck bump)")
    a("--stribeck-speed", type=float, default=0.02, help="rad/s")
    a("--sign-width", type=float, default=0.005, help="rad/s: the friction's sign is tanh(v/this)")
    a("--depth", type=float, default=None, help="fixed insertion depth, m (default: 0.10-0.20 slowly)")
    a("--noise-scale", type=float, default=1.0, help="effort, encoder and velocity noise times this")
    a("--velocity-noise", type=float, default=1e-3, help="rad/s on the logged velocity")
    a("--ar-sd", type=float, default=0.0, help="N.m: AR(1) effort noise beside the white (0: none)")
    a("--ar-time", type=float, default=0.1, help="s: the AR(1) noise's correlation time")


def truth(options):
    """The arm's true parameters, with --inertia-scale applied."""
    return {"inertia": [options.inertia_scale * j for j in options.inertia],
            "coupling": options.coupling, "viscous": list(options.viscous),
            "coulomb": options.coulomb, "static": options.static,
            "stribeck_speed": options.stribeck_speed, "sign_width": options.sign_width}


def friction(v, joint, arm):
    """This arm's friction (N.m): viscous plus a Stribeck curve with its own smooth sign."""
    level = arm["coulomb"] + (arm["static"] - arm["coulomb"]) * np.exp(-(v / arm["stribeck_speed"]) ** 2)
    return arm["viscous"][joint] * v + level * np.tanh(v / arm["sign_width"])


def trajectory(t, rng):
    """q, v, a (rad, rad/s, rad/s^2) of one joint: three sines, analytic derivatives.

    The amplitudes are scaled so that the peak angle is 0.4-0.8 rad, then
    lowered if the peak speed would pass 1 rad/s (a PSM's free motion)."""
    periods = rng.uniform(2.0, 8.0, 3)
    omega = 2 * np.pi / periods
    phase = rng.uniform(0, 2 * np.pi, 3)
    amplitude = rng.uniform(0.5, 1.0, 3)
    centre = rng.uniform(-0.1, 0.1)
    arg = np.outer(t, omega) + phase
    q = np.sin(arg) @ amplitude
    v = np.cos(arg) @ (amplitude * omega)
    a = -np.sin(arg) @ (amplitude * omega ** 2)
    scale = rng.uniform(0.4, 0.8) / np.max(np.abs(q))
    scale = min(scale, 1.0 / np.max(np.abs(v)))
    return centre + scale * q, scale * v, scale * a


def depth_path(t, options, rng):
    """Insertion depth (m): fixed, or one slow sine through 0.10-0.20 m (period 15-25 s)."""
    if options.depth is not None:
        return np.full_like(t, options.depth)
    period = rng.uniform(15.0, 25.0)
    return 0.15 + 0.05 * np.sin(2 * np.pi * t / period + rng.uniform(0, 2 * np.pi))


def ar1(n, dt, sd, tau, rng):
    """Stationary AR(1) noise of standard deviation sd and correlation time tau (s):
    defined by its time, so that it means the same at every rate."""
    if sd <= 0.0:
        return np.zeros(n)
    rho = np.exp(-dt / tau)
    w = rng.normal(0.0, sd * np.sqrt(1.0 - rho ** 2), n)
    w[0] = rng.normal(0.0, sd)
    out = np.empty(n)
    out[0] = w[0]
    for k in range(1, n):           # a plain loop: 30 000 rows take ~20 ms
        out[k] = rho * out[k - 1] + w[k]
    return out


def simulate(options, seed):
    """One free-motion log. Returns a dict: the log's columns ("columns", "rows",
    "metadata") and the truth ("q", "v", "a", "depth", "bias", "inertial",
    "friction", "noise": per joint arrays; "arm": the parameters)."""
    rng = np.random.default_rng(seed)
    arm = truth(options)
    dt = 1.0 / options.rate
    t = np.arange(int(round(options.duration * options.rate))) * dt
    n = len(t)
    q, v, a = zip(*(trajectory(t, rng) for _ in range(2)))
    depth = depth_path(t, options, rng)
    bias = generate.bias(q[0], q[1], depth, "none")
    # The mass matrix [[J1, C], [C, J2]]: each joint's effort feels the other's acceleration.
    inertial = [arm["inertia"][j] * a[j] + arm["coupling"] * a[1 - j] for j in range(2)]
    fric = [friction(v[j], j, arm) for j in range(2)]
    s = options.noise_scale
    noise = [rng.normal(0.0, EFFORT_NOISE * s, n) + ar1(n, dt, options.ar_sd, options.ar_time, rng)
             for _ in range(2)]
    tau = [bias[j] + inertial[j] + fric[j] + noise[j] for j in range(2)]
    encoder = [q[j] + rng.normal(0.0, ENCODER_NOISE * s, n) for j in range(2)]
    logged_v = [v[j] + rng.normal(0.0, options.velocity_noise * s, n) for j in range(2)]
    metadata = [
        ("generator", "experiments/second_generator/arm.py (numpy), seed %d" % seed),
        ("arm", "J %.4g / %.4g kg.m^2, coupling %.4g kg.m^2, viscous %.4g / %.4g N.m.s/rad, "
                "Coulomb %.4g N.m, static %.4g N.m below %.4g rad/s, sign width %.4g rad/s" % (
                    arm["inertia"][0], arm["inertia"][1], arm["coupling"], arm["viscous"][0],
                    arm["viscous"][1], arm["coulomb"], arm["static"], arm["stribeck_speed"],
                    arm["sign_width"])),
        ("protocol", "free motion at %g Hz, nothing touches the tip; effort noise %.4g N.m white%s" % (
            options.rate, EFFORT_NOISE * s,
            " + AR(1) %.4g N.m over %.3g s" % (options.ar_sd, options.ar_time) if options.ar_sd > 0 else "")),
    ]
    return {"columns": ["t", "q1", "q2", "q3", "tau1", "tau2", "v1", "v2"],
            "rows": [t, encoder[0], encoder[1], depth, tau[0], tau[1], logged_v[0], logged_v[1]],
            "metadata": metadata, "t": t, "q": q, "v": v, "a": a, "depth": depth, "bias": bias,
            "inertial": inertial, "friction": fric, "noise": noise, "arm": arm}


def write_log(path, sim):
    generate.write(path, sim["metadata"], sim["columns"], sim["rows"])


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("out")
    parser.add_argument("--seed", type=int, default=1)
    add_arguments(parser)
    options = parser.parse_args()
    sim = simulate(options, options.seed)
    write_log(options.out, sim)
    peak = max(np.max(np.abs(v)) for v in sim["v"])
    print("wrote %s: %d rows, peak speed %.2f rad/s" % (options.out, len(sim["t"]), peak))


if __name__ == "__main__":
    main()
