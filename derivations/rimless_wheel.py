"""McGeer's rimless wheel (Int. J. Robotics Research 9, 1990), built with
sympy.physics.mechanics and struck by rigidimpact at each spoke's landing.

A hub of mass m (its radius of gyration r about the hub) carries spokes of length l, a
half-angle alpha apart; it rolls down a slope gamma. When the next spoke lands (plastic,
no slip: e = 0, stick) the old one leaves the ground.

- ``speed_ratio``: the rolling rate just after a landing over the rate just before, in
  alpha, for the hub as a point mass (r = 0); ``speed_ratio_r`` the same with r.
  Derived on a floating wheel (hub position and rotation as coordinates) from the mass
  matrix and the landing spoke's partial velocities.
- ``omega_star``: the rolling speed just after each landing on the steady roll, for
  m = 1, l = 1, g = 9.8, alpha = pi/8, gamma = 0.08, by Newton's method on the Poincare
  map of the hybrid simulation (stance phase: the wheel pivoting on its spoke).

Run: ``python derivations/rimless_wheel.py [--json]``.
"""

from __future__ import annotations

import argparse
import json
import math
import time

import numpy as np
import sympy as sp
import sympy.physics.mechanics as me

import rigidimpact as ri

m, l, r, g, gamma, alpha = sp.symbols("m l r g gamma alpha", positive=True)
VALUES = {m: 1, l: 1, r: 0, g: sp.Rational(49, 5), alpha: sp.pi / 8,
          gamma: sp.Rational(8, 100)}


def landing():
    """The floating wheel's impact at the landing spoke: the rate after over before."""
    N, B = me.ReferenceFrame("N"), me.ReferenceFrame("B")
    x, y, theta = me.dynamicsymbols("x y theta")
    ux, uy, w = me.dynamicsymbols("u_x u_y omega")
    B.orient_axis(N, N.z, theta)
    B.set_ang_vel(N, w * N.z)
    hub = me.Point("hub")
    hub.set_vel(N, ux * N.x + uy * N.y)
    # the stance spoke points from the hub along -B.y; the landing one is 2 alpha ahead
    spoke = hub.locatenew("spoke", l * (sp.sin(2 * alpha) * B.x - sp.cos(2 * alpha) * B.y))
    spoke.v2pt_theory(hub, N, B)
    wheel = me.RigidBody("wheel", hub, B, m, (me.inertia(B, 0, 0, m * r**2), hub))
    kane = me.KanesMethod(N, [x, y, theta], [ux, uy, w],
                          [x.diff() - ux, y.diff() - uy, theta.diff() - w])
    kane.kanes_equations([wheel], [])
    solution = ri.mechanics.impact(kane, [ri.mechanics.contact(
        spoke, N.y, restitution=0, tangential="stick", name="spoke")], frame=N).solve()
    # just before: pivoting on the stance spoke's foot at theta = -alpha (leaning ahead)
    before = {theta: -alpha, ux: -l * w * sp.cos(-alpha), uy: -l * w * sp.sin(-alpha)}
    ratio = sp.simplify(solution.speeds_after[2].xreplace(before) / w)
    return solution, ratio


def roll(ratio):
    """The steady roll: stance phase on one spoke, then the landing map."""
    theta, w = me.dynamicsymbols("theta omega")
    N, B = me.ReferenceFrame("N"), me.ReferenceFrame("B")
    B.orient_axis(N, N.z, theta)
    B.set_ang_vel(N, w * N.z)
    foot = me.Point("foot")
    foot.set_vel(N, 0)
    hub = foot.locatenew("hub", l * B.y)
    hub.v2pt_theory(foot, N, B)
    kane = me.KanesMethod(N, [theta], [w], [theta.diff() - w])
    weight = m * g * (sp.sin(gamma) * N.x - sp.cos(gamma) * N.y)
    kane.kanes_equations([me.Particle("hub", hub, m)], [(hub, weight)])
    rhs = ri.mechanics.flow_of(kane, VALUES)
    a, k = float(VALUES[alpha]), float(ratio.xreplace(VALUES))
    wheel = ri.mechanics.Hybrid(
        rhs, gap=lambda x: math.cos(x[0]) - math.cos(x[0] + 2 * a),  # landing spoke's height
        jump=lambda x: np.array([x[0] + 2 * a, k * x[1]]),
        guard=lambda x: x[1] < 0, fallen=lambda x: x[1] > 0)
    return wheel.fixed_point(np.array([a, -1.0]), free=[1])


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--json", action="store_true")
    args = parser.parse_args(argv)
    start = time.perf_counter()
    _, ratio = landing()
    point_mass = sp.simplify(ratio.subs(r, 0))
    found = roll(ratio)
    out = {"speed_ratio": str(point_mass), "speed_ratio_r": str(ratio),
           "omega_star": float(-found.state[1]),
           "eigenvalues": [[float(z.real), float(z.imag)] for z in found.eigenvalues],
           "seconds": round(time.perf_counter() - start, 2)}
    if args.json:
        print(json.dumps(out, indent=2))
    else:
        print(f"rate after / rate before at a landing: {point_mass} (hub a point mass); "
              f"{ratio} with radius of gyration r")
        print(f"steady roll: {out['omega_star']:.10f} rad/s just after each landing")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
