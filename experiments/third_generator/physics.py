"""Physics of the third generator: an instrument in a PSM's cannula, joints 1-2.

Written from the JHU paper (Delta q = delta*sgn(tau_ext) + K(L)*tau_ext) and first
principles only; it shares no code or tables with pliant's simulator.

Conventions (see generate.py's docstring for the full statement):
  * q_enc  : motor-side encoder angle (what the log's q1, q2 hold, quantised).
  * q_tip  : the instrument's true angle (the log's q*_true).
  * q_tip = q_enc - Dq,  Dq = b + K(L)*tau_ext,  b in [-delta, +delta] the shaft's place in
    the clearance (a hysteretic function of tau_ext) -- so that pliant's corrected
    q_hat = q - delta*S - K*tau_ext equals q_tip once the shaft rests on a wall.
  * tau_ext: the torque the motor transmits through the shaft to whatever holds the tip;
    positive tau_ext drives the motor ahead (+) of the tip. Measured effort
    tau = tau0(q_enc, L) + tau_ext + coloured noise.
"""
import bisect
import math

import numpy as np

L_REF = 0.15  # m, reference depth of the compliance law


# ---------------------------------------------------------------- compliance K(L)
# Each joint: K(L) = scale * (Kc + K0 * (L / L_REF)**p), rad/(N*m): a rigid-joint part Kc in series
# with a shaft/structure part falling with depth as a power law (a tapered beam between
# cantilever-like p = -2 and a pure lever p = -1 lies near the values used here).
BASE_LAW = {
    1: dict(Kc=0.0256, K0=0.0368, p=-0.8),
    2: dict(Kc=0.0249, K0=0.0119, p=-1.3),
}


def compliance(joint, L, scale):
    law = BASE_LAW[joint]
    return scale * (law["Kc"] + law["K0"] * (np.asarray(L, float) / L_REF) ** law["p"])


# ---------------------------------------------------------------- backlash with hysteresis
class Clearance:
    """The shaft's place b in a clearance of half-width delta (rad, as a joint angle).

    Two monotone branches: the ascending one b_up(tau) stays at -delta until tau exceeds the
    breakaway threshold tau_h, then crosses the clearance over a further load width w along the
    take-up curve g (piecewise-linear preload spring, or exponential approach), reaching +delta
    at tau_h + w. The descending branch is its mirror. The state moves only when a branch pushes
    it: b <- clip(b, b_up(tau), b_down(tau)). An unloaded shaft therefore stays against the wall
    it last touched; it leaves only when the load reverses past -tau_h (a generalised play
    operator)."""

    def __init__(self, delta, tau_h, width, shape, b0):
        self.delta, self.tau_h, self.width, self.shape = delta, tau_h, width, shape
        self.b = float(b0)

    def take_up(self, x):
        """Fraction of the clearance crossed at normalised load x >= 0 beyond the threshold."""
        if x <= 0.0:
            return 0.0
        if x >= 1.0:
            return 1.0
        if self.shape == "preload":  # soft preload spring first, then a stiffer one
            xk, yk = 0.3, 0.7
            return yk * x / xk if x < xk else yk + (1 - yk) * (x - xk) / (1 - xk)
        a = 3.0  # exponential approach, normalised to reach the wall at x = 1
        return (1.0 - math.exp(-a * x)) / (1.0 - math.exp(-a))

    def branches(self, tau):
        up = -self.delta + 2 * self.delta * self.take_up((tau - self.tau_h) / self.width)
        down = self.delta - 2 * self.delta * self.take_up((-tau - self.tau_h) / self.width)
        return up, down

    def peek(self, tau):
        up, down = self.branches(tau)
        return min(max(self.b, up), down)

    def apply(self, tau):
        self.b = self.peek(tau)
        return self.b

    def full_load(self):
        """Load beyond which the shaft rests on a wall whatever its history."""
        return self.tau_h + self.width


def solve_held_load(clr, K, gap):
    """tau_ext such that clr.peek(tau) + K*tau = gap (gap = q_enc - q_tip), by bisection.

    The left side is strictly increasing in tau (K > 0, the branches are monotone)."""
    lo, hi = -20.0, 20.0
    for _ in range(80):
        mid = 0.5 * (lo + hi)
        if clr.peek(mid) + K * mid < gap:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


# ---------------------------------------------------------------- bias torque tau0(q, L)
class Bias:
    """Gravity/counterbalance-like bias torques (N*m), not a table.

    joint 1 (yaw):   c1 + a1*cos(q2)*sin(q1 + phi1) + b1*cos(q2)
    joint 2 (pitch): c2 + a2*sin(q2 + phi2) + m*(L - Lcw)*sin(q2 + phi3) + e2*sin(2*q2)
    The depth term is the instrument's moment about the pitch axis growing as it is inserted past
    the counterweight's balance depth Lcw."""

    def __init__(self, rng):
        u = rng.uniform
        self.c1, self.a1, self.b1, self.phi1 = u(0.12, 0.22), u(0.03, 0.08), u(0.02, 0.05), u(-0.5, 0.5)
        self.c2, self.a2, self.phi2 = u(-0.28, -0.15), u(0.08, 0.16), u(-0.6, 0.2)
        self.m, self.Lcw, self.phi3, self.e2 = u(0.6, 1.2), u(0.11, 0.15), u(-0.3, 0.3), u(0.005, 0.02)
        self.cross = True

    def tau0(self, q1, q2, L):
        q1, q2, L = (np.asarray(x, float) for x in (q1, q2, L))
        c2q = np.cos(q2) if self.__dict__.get("cross", True) else np.ones_like(q2)
        t1 = self.c1 + self.a1 * c2q * np.sin(q1 + self.phi1) + self.b1 * c2q
        t2 = (self.c2 + self.a2 * np.sin(q2 + self.phi2) + self.m * (L - self.Lcw) * np.sin(q2 + self.phi3)
              + self.e2 * np.sin(2 * q2))
        return t1, t2

    def as_dict(self):
        return dict(self.__dict__)


# ---------------------------------------------------------------- sensors
class AR1:
    """Coloured effort noise: x[k+1] = phi*x[k] + sqrt(1-phi^2)*sigma*w, phi = exp(-dt/tc)."""

    def __init__(self, rng, sigma, tc):
        self.rng, self.sigma, self.tc = rng, sigma, tc
        self.x = rng.normal(0.0, sigma)

    def step(self, dt):
        phi = math.exp(-dt / self.tc)
        self.x = phi * self.x + math.sqrt(1 - phi * phi) * self.sigma * self.rng.normal()
        return self.x

    def fresh(self):
        """A draw independent of the past (a new pose after a long settling)."""
        self.x = self.rng.normal(0.0, self.sigma)
        return self.x


def quantise(q, count):
    return np.round(np.asarray(q, float) / count) * count


# ---------------------------------------------------------------- hidden effects (--effect NAME)
# One physical effect the paper's model lacks, added on top of everything above. Written from
# first principles for this generator alone; the names are pliant's catalogue names so that a
# diagnosis can be scored, nothing else is shared. The effect's constants are fixed numbers (no
# random draws), so an effect never touches the instrument's random stream.
EFFECT_NAMES = ("none", "deflection_coupling", "effort_drift", "load_dependent_compliance", "held_friction",
                "effort_delay", "backlash_depth", "bias_torque_cross_joint")

EFFECT_DEFAULTS = {
    "none": {},
    # symmetric off-diagonal compliance (Maxwell reciprocity): k12 = k21 = c*sqrt(K1*K2), rad/(N*m)
    "deflection_coupling": dict(c=0.3),
    # effort sensor offset drifting linearly in time, N*m per minute per joint; the quasi-static
    # calibration's poses are spaced pose_s seconds apart (settling + averaging)
    "effort_drift": dict(rate_per_min=[0.05, 0.05], pose_s=0.3),
    # secant compliance K_eff = K*(1 - a*|tau|/tau_u) (a stiffening) up to |tau| = tau_c, then the
    # deflection continues with the tangent slope there (kept monotone)
    "load_dependent_compliance": dict(a=0.25, tau_u=1.0, tau_c=1.5),
    # Coulomb friction in the drive, between the motor and the effort sensor's load path: the
    # effort reads tau0 + tau_ext + f, f a play (Dahl-like) state of the motor angle with a linear
    # presliding zone z (rad) that saturates at +-Fc after a motion in either direction and holds
    "held_friction": dict(Fc=[0.08, 0.08], z=5e-4),
    # the recorded effort is the true one delayed by lag seconds (quasi-static poses are unaffected)
    "effort_delay": dict(lag=0.025),
    # clearance half-width delta(L) = delta*max(floor, 1 + g*(L - L0)/dL)
    "backlash_depth": dict(g=2.0, L0=0.155, dL=0.1, floor=0.25),
    # joint 1's bias gains amp*sin(2*q2): zero on joint 1's own sweep (q2 = 0)
    "bias_torque_cross_joint": dict(amp=0.05),
}


class Effect:
    """The hidden effect's physics and its per-log state (friction, delay line)."""

    def __init__(self, name, delta0):
        if name not in EFFECT_NAMES:
            raise ValueError(f"unknown effect {name!r}; one of {', '.join(EFFECT_NAMES)}")
        self.name, self.p, self.delta0 = name, dict(EFFECT_DEFAULTS[name]), list(delta0)
        self.reset()

    @property
    def active(self):
        return self.name != "none"

    def reset(self):
        """Fresh per-log state: friction at zero, empty delay line."""
        self.f, self.qprev = [0.0, 0.0], [None, None]
        self.ht, self.he = [], [[], []]

    def describe(self):
        return dict(name=self.name, params=self.p)

    # ---- mechanics
    def bend(self, K, tau):
        """Elastic deflection of a joint of nominal compliance K under load tau (rad)."""
        if self.name != "load_dependent_compliance":
            return K * tau
        a, tu, tc = self.p["a"] / self.p["tau_u"], self.p["tau_u"], self.p["tau_c"]
        s, m = (1.0 if tau >= 0 else -1.0), abs(tau)
        if m <= tc:
            return K * tau * (1.0 - a * m)
        return s * K * (tc * (1.0 - a * tc) + (m - tc) * (1.0 - 2.0 * a * tc))

    def coupling(self, K1, K2):
        if self.name != "deflection_coupling":
            return 0.0
        return self.p["c"] * math.sqrt(K1 * K2)

    def set_depth(self, clrs, L):
        """Depth-dependent clearance: rescale delta and the shaft's place in it (relative place kept)."""
        if self.name != "backlash_depth":
            return
        p = self.p
        fac = max(p["floor"], 1.0 + p["g"] * (float(L) - p["L0"]) / p["dL"])
        for j, c in enumerate(clrs):
            new = self.delta0[j] * fac
            if new != c.delta:
                c.b *= new / c.delta
                c.delta = new

    def solve_held(self, clrs, Ks, gaps, guess):
        """tau_ext on both joints of a held tip: peek_i(tau_i) + bend(K_i, tau_i) + k*tau_other = gap_i.

        Gauss-Seidel over the joints (contraction: k^2/(K1*K2) = c^2 < 1), bisection per joint."""
        k = self.coupling(Ks[0], Ks[1])
        tau = list(guess)
        for _ in range(60 if k else 1):
            old = list(tau)
            for i in range(2):
                tau[i] = solve_held_load_fn(clrs[i], lambda t, i=i: self.bend(Ks[i], t),
                                            gaps[i] - k * tau[1 - i])
            if max(abs(tau[0] - old[0]), abs(tau[1] - old[1])) < 1e-13:
                break
        return tau

    # ---- effort sensor
    def drive_torque(self, j, qm, q2):
        """Torque the drive adds to the effort at motor angle qm (friction, extra bias)."""
        extra = 0.0
        if self.name == "held_friction":
            if self.qprev[j] is not None:
                fc, z = self.p["Fc"][j], self.p["z"]
                self.f[j] = min(fc, max(-fc, self.f[j] + fc * (qm - self.qprev[j]) / z))
            self.qprev[j] = qm
            extra += self.f[j]
        if self.name == "bias_torque_cross_joint" and j == 0:
            extra += self.p["amp"] * math.sin(2.0 * q2)
        return extra

    def record(self, t, true_eff):
        """What the sensor records at time t of the true efforts (delay line, drift); no noise."""
        out = list(true_eff)
        if self.name == "effort_delay":
            self.ht.append(t)
            for j in range(2):
                self.he[j].append(true_eff[j])
            td = t - self.p["lag"]
            if td <= self.ht[0]:
                out = [self.he[j][0] for j in range(2)]
            else:
                k = bisect.bisect_left(self.ht, td)  # ht[k-1] < td <= ht[k]
                w = (td - self.ht[k - 1]) / (self.ht[k] - self.ht[k - 1])
                out = [self.he[j][k - 1] + w * (self.he[j][k] - self.he[j][k - 1]) for j in range(2)]
        if self.name == "effort_drift":
            out = [out[j] + self.p["rate_per_min"][j] * t / 60.0 for j in range(2)]
        return out


def solve_held_load_fn(clr, bend, gap):
    """solve_held_load with a monotone deflection law bend(tau) in place of K*tau."""
    lo, hi = -20.0, 20.0
    for _ in range(80):
        mid = 0.5 * (lo + hi)
        if clr.peek(mid) + bend(mid) < gap:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)
