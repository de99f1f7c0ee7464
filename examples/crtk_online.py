#!/usr/bin/env python3
"""Correct a dVRK PSM's joints 1-2 online with pliant's filter, over CRTK (ROS 2, dVRK 2.x).

    python3 examples/crtk_online.py --params identified.json --arm PSM1

Each period it reads the arm's measured joint state through crtk_python_client
(``jp, jv, jf, t = arm.measured_js()``: positions in rad (joint 3 in m),
efforts in N·m (joint 3 in N), the stamp in s), steps a ``pliant.Filter``, and
prints the corrected joints 1-2 (rad) with their σ: a six-joint position list
with joints 1-2 replaced, ready for a controller or a virtual fixture.

What is tested, and what is not: the ROS-free core below (``filter_sample``,
``corrected_positions``, ``correct_stream``) is run by this repository's
tests (python/tests/test_crtk_online.py) against ``pliant filter`` on a
shipped log. The ROS 2 part (``main``: crtk_python_client, a running dVRK
console) cannot run in this repository's CI, which has neither ROS 2 nor an
arm: it has not been run here. It needs a sourced ROS 2 workspace with
crtk_python_client and ``import pliant`` working (docs/python.md).
"""

import argparse
import sys

import numpy as np

import pliant


def filter_sample(jp, jf, t):
    """One measured_js reading as the filter's sample:
    (t s, q1 rad, q2 rad, q3 m, tau1 N·m, tau2 N·m)."""
    return np.array([t, jp[0], jp[1], jp[2], jf[0], jf[1]], dtype=np.float64)


def corrected_positions(jp, estimate):
    """The arm's joint positions with joints 1-2 replaced by the filter's corrected angles."""
    positions = [float(q) for q in jp]
    positions[0], positions[1] = float(estimate.corrected[0]), float(estimate.corrected[1])
    return positions


def correct_stream(online_filter, readings):
    """For each (jp, jv, jf, t) reading: (corrected positions, (σ1, σ2) in rad, estimate)."""
    for jp, _jv, jf, t in readings:
        estimate = online_filter.step(filter_sample(jp, jf, t))
        yield corrected_positions(jp, estimate), tuple(float(s) for s in estimate.sd), estimate


def measured_js_readings(ral, arm, rate_hz):
    """measured_js tuples from a CRTK arm at rate_hz until ROS shuts down (ROS 2 only)."""
    rate = ral.create_rate(rate_hz)
    while not ral.is_shutdown():
        yield arm.measured_js()
        rate.sleep()


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--params", required=True, help="parameters file (pliant identify)")
    parser.add_argument("--arm", default="PSM1", help="CRTK arm namespace, e.g. PSM1")
    parser.add_argument("--rate", type=float, default=500.0, help="readings per second, Hz")
    parser.add_argument("--print-every", type=int, default=100, help="print one reading in N")
    args = parser.parse_args(argv)

    import crtk  # crtk_python_client: imported here so the core above needs no ROS

    class Arm:
        """The one CRTK feature this example reads: measured_js."""

        def __init__(self, ral, name):
            self.ral = ral.create_child(name)
            self.crtk_utils = crtk.utils(self, self.ral)
            self.crtk_utils.add_measured_js()

    ral = crtk.ral("pliant_crtk_online")
    arm = Arm(ral, args.arm)
    ral.check_connections()
    ral.spin()
    online_filter = pliant.Filter(pliant.load_parameters(args.params),
                                  sample_period_s=1.0 / args.rate)
    readings = measured_js_readings(ral, arm, args.rate)
    for n, (positions, sd, estimate) in enumerate(correct_stream(online_filter, readings)):
        if n % args.print_every == 0:
            print(f"q1 {positions[0]:+.6f} ± {sd[0]:.2e} rad   q2 {positions[1]:+.6f} ± "
                  f"{sd[1]:.2e} rad   flags {estimate.flags:#04x}", flush=True)
    ral.shutdown()
    return 0


if __name__ == "__main__":
    sys.exit(main())
