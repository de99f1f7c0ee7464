#!/usr/bin/python3
"""Third, independent log generator for pliant: a calibration log and a divot-push test log.

Physics (physics.py), written from the JHU paper and first principles only:

  Sign convention (checked against docs/correction.md and the paper's eq. 1-2):
      q_tip = q_enc - Dq,   Dq = b(tau_ext history) + K(L)*tau_ext
  so pliant's corrected q_hat = q - delta*S(tau_ext) - K(L)*tau_ext equals q_tip (the log's
  q*_true) whenever the shaft rests on a wall (b = delta*sgn(tau_ext)). tau_ext is the torque the
  motor transmits to whatever holds the tip; a positive tau_ext puts the motor ahead of the tip
  and raises the measured effort tau = tau0(q_enc, L) + tau_ext + noise.

  * K(L) = s_j*(Kc + K0*(L/0.15)^p), p = -0.8 (yaw) / -1.3 (pitch), s_j the instrument's factor.
  * b: a clearance of half-width delta crossed along a piecewise-linear preload spring (yaw) or an
    exponential approach (pitch) between loads tau_h and tau_h + w, with hysteresis: an unloaded
    shaft stays at the wall it last touched, also through free motion, until the load reverses
    past tau_h. A free tip (tau_ext = 0) is therefore at q_enc - b, |b| <= delta.
  * tau0: trigonometric gravity/counterbalance terms, joint 1 depending on q2, joint 2 on depth.
  * effort noise AR(1), encoder quantised (counts of 2e-5 rad), depth to 1 um, tracker q*_ref =
    q_tip + white noise.

Experiments (canonical pliant CSV, docs/log-format.md):
  calibration.csv  '# timing: quasi-static', one row per pose = mean of 20 samples at 1 kHz:
                   free bias sweeps (+-0.5 rad in 5 deg steps, each joint, 4 depths) and clamped
                   holds at 6 depths, each joint stepped to +-1.2 N*m of effort change and back.
  test.csv         time-stamped at --rate: divot holds at 4 depths, each with 1-2 pushes of
                   0.3-1.0 N*m in varying directions, free motion of 0.5-1 s between them.
  truth.json       every true parameter, K and delta at the clamp and test depths.
  *_truth.csv      per row: the true tau_ext, b and K (for sanity checks only).

Hidden effects (--effect NAME, physics.Effect; default none = the paper's model only). ONE
effect the paper's model lacks, in both logs; fixed constants, no random draws; the test log's
random stream is kept identical to --effect none's (paired logs, see main()):
  deflection_coupling        Dq1 += k*tau2_ext, Dq2 += k*tau1_ext, k = 0.3*sqrt(K1*K2) (symmetric)
  effort_drift               effort += 0.05 N*m/min * t per joint (calibration poses 0.3 s apart)
  load_dependent_compliance  K -> K*(1 - 0.25*|tau_ext|/1 N*m) (secant; monotone beyond 1.5 N*m)
  held_friction              effort += f, Coulomb 0.08 N*m in the drive, play state of the motor
                             angle with a 0.5 mrad presliding zone (holds at rest)
  effort_delay               recorded effort = true effort 25 ms earlier (test log; the quasi-
                             static calibration poses are settled and unaffected)
  backlash_depth             delta(L) = delta*max(0.25, 1 + 2*(L - 0.155)/0.1)
  bias_torque_cross_joint    joint 1's bias += 0.05*sin(2*q2) (zero along joint 1's own sweep)

Usage: generate.py [--seed N] [--k-scale K1 K2] [--clearance D1 D2] [--noise-scale X]
                   [--rate HZ] [--out DIR] [--effect NAME]  (clearance in rad)
       diagnostics: [--effort-tc SECONDS] [--no-cross-bias]
"""
import argparse
import copy
import json
import math
import os

import numpy as np

import physics as ph

COUNT = 2e-5          # rad per encoder count
DEPTH_COUNT = 1e-6    # m
SWEEP_DEPTHS = [0.09, 0.13, 0.18, 0.23]
CLAMP_DEPTHS = [0.08, 0.11, 0.14, 0.17, 0.20, 0.23]
COLS = ["t", "q1", "q2", "q3", "tau1", "tau2", "q1_true", "q2_true", "q1_ref", "q2_ref", "tip_fixed", "segment"]


class Instrument:
    def __init__(self, args):
        rng = np.random.default_rng(args.seed)
        self.rng = rng
        self.kscale = list(args.k_scale) if args.k_scale else [float(rng.uniform(0.7, 1.4)) for _ in range(2)]
        self.delta = list(args.clearance) if args.clearance else [float(rng.uniform(3e-3, 12e-3)) for _ in range(2)]
        tau_h = [float(rng.uniform(0.02, 0.05)), float(rng.uniform(0.02, 0.05))]
        width = [float(rng.uniform(0.08, 0.2)), float(rng.uniform(0.12, 0.3))]
        shapes = ["preload", "exponential"]
        self.clr = [ph.Clearance(self.delta[j], tau_h[j], width[j], shapes[j], rng.choice([-1, 1]) * self.delta[j])
                    for j in range(2)]
        self.bias = ph.Bias(rng)
        self.sigma = [float(rng.uniform(0.005, 0.02)) * args.noise_scale for _ in range(2)]
        self.tc = [float(rng.uniform(0.005, 0.03)) for _ in range(2)]
        if args.effort_tc is not None:  # diagnostic: override the noise's correlation time
            self.tc = [args.effort_tc, args.effort_tc]
        if args.no_cross_bias:  # diagnostic: joint 1's bias independent of q2
            self.bias.cross = False
        self.noise = [ph.AR1(rng, self.sigma[j], self.tc[j]) for j in range(2)]
        self.ref_sd = float(rng.uniform(2e-4, 5e-4))
        self.jitter = 3e-6  # servo jitter of the motor about its setpoint, rad

    def K(self, j, L):
        return float(ph.compliance(j + 1, L, self.kscale[j]))

    def truth(self, test_depths):
        per_depth = lambda Ls: [dict(L=L, K1=self.K(0, L), K2=self.K(1, L)) for L in Ls]
        return dict(k_scale=self.kscale, delta=self.delta, law=ph.BASE_LAW, L_ref=ph.L_REF,
                    tau_h=[c.tau_h for c in self.clr], width=[c.width for c in self.clr],
                    shape=[c.shape for c in self.clr], full_load=[c.full_load() for c in self.clr],
                    bias=self.bias.as_dict(), effort_sigma=self.sigma, effort_tc=self.tc,
                    ref_sd=self.ref_sd, encoder_count=COUNT, clamp=per_depth(CLAMP_DEPTHS),
                    test=per_depth(test_depths), sweep_depths=SWEEP_DEPTHS)


class Recorder:
    def __init__(self):
        self.rows, self.truth = [], []

    def add(self, row, truth):
        self.rows.append(row)
        self.truth.append(truth)

    def write(self, path, meta, tpath):
        with open(path, "w") as f:
            for k, v in meta:
                f.write(f"# {k}: {v}\n")
            f.write(",".join(COLS) + "\n")
            for r in self.rows:
                f.write(",".join(fmt(c, r[c]) for c in COLS) + "\n")
        with open(tpath, "w") as f:
            f.write("t,tau1_ext,tau2_ext,b1,b2,K1,K2\n")
            for r, tr in zip(self.rows, self.truth):
                f.write(fmt("t", r["t"]) + "," + ",".join("%.12g" % x for x in tr) + "\n")


def fmt(col, v):
    if col in ("tip_fixed", "segment"):
        return str(int(v))
    return "%.12g" % v


# ------------------------------------------------------------------ calibration (quasi-static)
class Calibration:
    def __init__(self, ins, effect=None):
        self.ins, self.rec, self.seg, self.k = ins, Recorder(), 0, 0
        self.qm = [0.0, 0.0]
        self.fx = effect if effect is not None and effect.active else None

    def pose(self, L, held, tip, text):
        """One row: the mean of 20 samples at 1 kHz after settling."""
        ins, n = self.ins, 20
        text_true = text
        enc = [np.mean(ph.quantise(self.qm[j] + ins.rng.normal(0, ins.jitter, n), COUNT)) for j in range(2)]
        t0 = ins.bias.tau0(self.qm[0], self.qm[1], L)
        if self.fx:  # settled pose: the drive's torque at the motor angle, the sensor at pose time
            fx = self.fx
            true = [t0[j] + text[j] + fx.drive_torque(j, self.qm[j], self.qm[1]) for j in range(2)]
            true = fx.record(self.k * fx.p.get("pose_s", 0.0), true) if fx.name == "effort_drift" else true
            t0, text = [true[0], true[1]], [0.0, 0.0]
        eff = []
        for j in range(2):
            ins.noise[j].fresh()
            eff.append(t0[j] + text[j] + np.mean([ins.noise[j].step(1e-3) for _ in range(n)]))
        qtrue = [tip[j] if held else self.qm[j] - ins.clr[j].b for j in range(2)]
        ref = [qtrue[j] + ins.rng.normal(0, ins.ref_sd / math.sqrt(n)) for j in range(2)]
        row = dict(t=self.k, q1=enc[0], q2=enc[1], q3=float(ph.quantise(L, DEPTH_COUNT)), tau1=eff[0],
                   tau2=eff[1], q1_true=qtrue[0], q2_true=qtrue[1], q1_ref=ref[0], q2_ref=ref[1],
                   tip_fixed=int(held), segment=self.seg)
        self.rec.add(row, [text_true[0], text_true[1], ins.clr[0].b, ins.clr[1].b, ins.K(0, L), ins.K(1, L)])
        self.k += 1
        return eff

    def free(self, L):
        if self.fx:
            self.fx.set_depth(self.ins.clr, L)
        for c in self.ins.clr:
            c.apply(0.0)
        return self.pose(L, False, None, [0.0, 0.0])

    def sweeps(self):
        step = math.radians(5.0)
        grid = np.arange(-0.5, 0.5 + 1e-9, step)
        for L in SWEEP_DEPTHS:
            for j in range(2):
                self.seg += 1
                for q in list(grid) + list(grid[::-1] + step / 2)[1:]:
                    self.qm = [0.0, 0.0]
                    self.qm[j] = float(q)
                    self.free(L)

    def clamps(self):
        ins = self.ins
        for L in CLAMP_DEPTHS:
            for j in range(2):
                self.seg += 1
                self.qm = [float(ins.rng.uniform(-0.25, 0.25)), float(ins.rng.uniform(-0.2, 0.2))]
                e0 = self.free(L)[j]
                tip = [self.qm[i] - ins.clr[i].b for i in range(2)]
                start, dq = self.qm[j], 0.3e-3 / L
                text = [0.0, 0.0]
                for direction, until in ((+1, lambda e, q: e - e0 >= 1.2), (-1, lambda e, q: e - e0 <= -1.2),
                                         (+1, lambda e, q: q >= start)):
                    while True:
                        self.qm[j] += direction * dq
                        if self.fx:
                            text = self.fx.solve_held(ins.clr, [ins.K(0, L), ins.K(1, L)],
                                                      [self.qm[i] - tip[i] for i in range(2)], text)
                            for i in range(2):
                                ins.clr[i].apply(text[i])
                        else:
                            for i in range(2):
                                text[i] = ph.solve_held_load(ins.clr[i], ins.K(i, L), self.qm[i] - tip[i])
                                ins.clr[i].apply(text[i])
                        eff = self.pose(L, True, tip, text)
                        if until(eff[j], self.qm[j]):
                            break


# ------------------------------------------------------------------ test log (time-stamped)
class DivotRun:
    def __init__(self, ins, rate, effect=None):
        self.ins, self.dt, self.rec = ins, 1.0 / rate, Recorder()
        self.fx = effect if effect is not None and effect.active else None
        self.t, self.seg = 0.0, 0
        self.qm, self.L = [0.0, 0.0], 0.15
        self.tip, self.held = None, False

    def sample(self, text):
        ins, dt = self.ins, self.dt
        if self.fx:
            self.fx.set_depth(ins.clr, self.L)
        enc = [float(ph.quantise(self.qm[j] + ins.rng.normal(0, ins.jitter), COUNT)) for j in range(2)]
        t0 = ins.bias.tau0(self.qm[0], self.qm[1], self.L)
        if self.fx:
            fx = self.fx
            true = [t0[j] + text[j] + fx.drive_torque(j, self.qm[j], self.qm[1]) for j in range(2)]
            rec = fx.record(self.t, true)
            eff = [rec[j] + ins.noise[j].step(dt) for j in range(2)]
        else:
            eff = [t0[j] + text[j] + ins.noise[j].step(dt) for j in range(2)]
        qtrue = list(self.tip) if self.held else [self.qm[j] - ins.clr[j].b for j in range(2)]
        ref = [qtrue[j] + ins.rng.normal(0, ins.ref_sd) for j in range(2)]
        row = dict(t=self.t, q1=enc[0], q2=enc[1], q3=float(ph.quantise(self.L, DEPTH_COUNT)), tau1=eff[0],
                   tau2=eff[1], q1_true=qtrue[0], q2_true=qtrue[1], q1_ref=ref[0], q2_ref=ref[1],
                   tip_fixed=int(self.held), segment=self.seg)
        self.rec.add(row, [text[0], text[1], ins.clr[0].b, ins.clr[1].b, ins.K(0, self.L), ins.K(1, self.L)])
        self.t += dt

    def rest(self, T):
        for _ in range(max(1, int(round(T / self.dt)))):
            self.load([0.0, 0.0]) if self.held else self.sample([0.0, 0.0])

    def move(self, q1, q2, L, T):
        """Free motion along a minimum-jerk path (peak speed 1.875*distance/T)."""
        assert not self.held
        a, b = self.qm + [self.L], [q1, q2, L]
        n = max(1, int(round(T / self.dt)))
        for k in range(1, n + 1):
            s = k / n
            s = 10 * s**3 - 15 * s**4 + 6 * s**5
            self.qm = [a[0] + (b[0] - a[0]) * s, a[1] + (b[1] - a[1]) * s]
            self.L = a[2] + (b[2] - a[2]) * s
            self.sample([0.0, 0.0])

    def load(self, text):
        """Held tip: the arm applies text; the motor sits where the shaft's bend puts it."""
        if self.fx:
            ins, L = self.ins, self.L
            k = self.fx.coupling(ins.K(0, L), ins.K(1, L))
            for j in range(2):
                b = ins.clr[j].apply(text[j])
                self.qm[j] = self.tip[j] + b + self.fx.bend(ins.K(j, L), text[j]) + k * text[1 - j]
            self.sample(text)
            return
        for j in range(2):
            b = self.ins.clr[j].apply(text[j])
            self.qm[j] = self.tip[j] + b + self.ins.K(j, self.L) * text[j]
        self.sample(text)

    def push(self, A, theta, Tr, Th):
        ramp = lambda s: 0.5 - 0.5 * math.cos(math.pi * s)
        nr, nh = int(round(Tr / self.dt)), int(round(Th / self.dt))
        prof = [ramp(k / nr) for k in range(1, nr + 1)] + [1.0] * nh + [ramp(1 - k / nr) for k in range(1, nr + 1)]
        for f in prof:
            self.load([A * f * math.cos(theta), A * f * math.sin(theta)])

    def contact(self, on):
        for c in self.ins.clr:
            c.apply(0.0)
        self.seg += 1
        self.held = on
        if on:
            self.tip = [self.qm[j] - self.ins.clr[j].b for j in range(2)]

    def run(self, depths):
        rng = self.ins.rng
        self.rest(0.5)
        for L in depths:
            self.move(float(rng.uniform(-0.2, 0.2)), float(rng.uniform(-0.2, 0.2)), L, 1.2)
            for _ in range(5):
                d = rng.uniform(-0.15, 0.15, 2)
                q = np.clip(np.array(self.qm) + d, -0.4, 0.4)
                T = max(float(rng.uniform(0.5, 1.0)), 1.875 * float(np.max(np.abs(q - self.qm))) / 0.28)
                self.move(float(q[0]), float(q[1]), L, T)
                self.rest(0.15)
                self.contact(True)
                self.rest(0.2)
                theta = float(rng.choice([0, 0.5, 1, 1.5]) * math.pi + rng.uniform(-0.5, 0.5))
                for k in range(int(rng.integers(1, 3))):
                    if k:
                        theta += math.pi + float(rng.uniform(-0.7, 0.7))
                        self.rest(0.2)
                    self.push(float(rng.uniform(0.3, 1.0)), theta, float(rng.uniform(0.4, 0.8)),
                              float(rng.uniform(0.3, 0.6)))
                self.rest(0.2)
                self.contact(False)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--seed", type=int, default=7)
    ap.add_argument("--k-scale", type=float, nargs=2, metavar=("K1", "K2"))
    ap.add_argument("--clearance", type=float, nargs=2, metavar=("D1", "D2"), help="delta per joint, rad")
    ap.add_argument("--noise-scale", type=float, default=1.0)
    ap.add_argument("--rate", type=float, default=400.0)
    ap.add_argument("--out", default="/tmp/third/default")
    ap.add_argument("--effort-tc", type=float, help="diagnostic: effort-noise correlation time, s (default drawn 5-30 ms)")
    ap.add_argument("--no-cross-bias", action="store_true", help="diagnostic: joint 1's bias without its cos(q2) factor")
    ap.add_argument("--effect", default="none", choices=ph.EFFECT_NAMES,
                    help="one hidden physical effect the paper's model lacks, in both logs (default none)")
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    ins = Instrument(args)
    effect = ph.Effect(args.effect, ins.delta)
    if effect.active:
        # Paired logs: the effect can change how many calibration poses are taken (the clamps stop
        # on the measured effort), which would shift the random stream the test log draws from.
        # Run the calibration with the effect on a copy of the instrument, then advance the
        # original exactly as --effect none does, so the test log differs from --effect none's by
        # the effect alone (same instrument, depths, pushes and noise).
        ins_fx = copy.deepcopy(ins)
        cal = Calibration(ins_fx, effect)
        cal.sweeps()
        cal.clamps()
        plain = Calibration(ins)
        plain.sweeps()
        plain.clamps()
        effect.reset()
        effect.set_depth(ins.clr, 0.15)  # the test log starts at L = 0.15
    else:
        cal = Calibration(ins)
        cal.sweeps()
        cal.clamps()
    meta = [("robot", "PSM1 (synthetic)"), ("instrument", "third_generator instrument"),
            ("generator", f"experiments/third_generator seed={args.seed}")]
    cal.rec.write(os.path.join(args.out, "calibration.csv"), meta + [("timing", "quasi-static")],
                  os.path.join(args.out, "calibration_truth.csv"))
    depths = sorted(float(x) for x in ins.rng.uniform(0.095, 0.225, 4))
    run = DivotRun(ins, args.rate, effect)
    run.run(depths)
    run.rec.write(os.path.join(args.out, "test.csv"), meta + [("rate_hz", args.rate)],
                  os.path.join(args.out, "test_truth.csv"))
    truth = ins.truth(depths)
    truth.update(seed=args.seed, rate=args.rate, noise_scale=args.noise_scale,
                 rows=dict(calibration=len(cal.rec.rows), test=len(run.rec.rows)), duration_s=run.t)
    if effect.active:
        truth.update(effect=effect.describe())
    with open(os.path.join(args.out, "truth.json"), "w") as f:
        json.dump(truth, f, indent=1)
    print(f"wrote {args.out}: calibration {len(cal.rec.rows)} rows, test {len(run.rec.rows)} rows "
          f"({run.t:.1f} s at {args.rate:g} Hz); K scale {ins.kscale}, delta {ins.delta}"
          + (f"; effect {effect.name}" if effect.active else ""))


if __name__ == "__main__":
    main()
