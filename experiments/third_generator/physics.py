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
