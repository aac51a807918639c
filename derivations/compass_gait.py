"""The compass-gait biped of Goswami, Thuilot and Espiau (1996 report; IJRR 17, 1998),
built with sympy.physics.mechanics and struck at heel strike by rigidimpact.

Two legs of length l = a + b, each a point mass m at a from its foot, joined at a hip of
mass m_H, walk down a slope of angle gamma. At heel strike the swing foot meets the
slope plastically and without slip (e = 0, stick) and the old stance foot leaves the
ground; the legs then swap roles.

- ``impact_map``: the 2x2 matrix over m, m_H, a, b and alpha (the half angle between the
  legs at impact) that takes [stance rate, swing rate] just before heel strike to the same
  after it, the legs relabelled (so the new stance rate is the old swing leg's). Derived
  on a floating model (the stance foot's position as two more coordinates), from the
  system's mass matrix and the swing foot's partial velocities.
- ``fixed_point``: [theta_st, theta_sw, thetadot_st, thetadot_sw] just after heel strike
  on the period-one gait for m = 5, m_H = 10, a = b = 0.5, g = 9.8 and a 3 degree slope,
  by Newton's method on the Poincare map of the hybrid simulation; angles from the true
  vertical, counterclockwise positive, walking downhill toward +x (the stance leg leans
  back, theta_st > 0, just after heel strike). ``eigenvalues``: of the map's Jacobian
  over (theta_st, thetadot_st, thetadot_sw).

Run: ``python derivations/compass_gait.py [--json]``.
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

m, m_H, a, b, g, gamma, alpha = sp.symbols("m m_H a b g gamma alpha", positive=True)
VALUES = {m: 5, m_H: 10, a: sp.Rational(1, 2), b: sp.Rational(1, 2), g: sp.Rational(49, 5),
          gamma: 3 * sp.pi / 180}


def legs(floating: bool):
    """The biped as a KanesMethod: the stance foot pinned at O (the flow), or free at
    (x, y) (the impact). Coordinates in the slope's frame: x down the slope, y out of it;
    leg angles from the slope's normal, counterclockwise positive."""
    N = me.ReferenceFrame("N")
    O = me.Point("O")
    O.set_vel(N, 0)
    st, sw = me.dynamicsymbols("theta_st theta_sw")
    w_st, w_sw = me.dynamicsymbols("omega_st omega_sw")
    q, u = [st, sw], [w_st, w_sw]
    if floating:
        x, y, ux, uy = me.dynamicsymbols("x y u_x u_y")
        foot = O.locatenew("foot", x * N.x + y * N.y)
        foot.set_vel(N, ux * N.x + uy * N.y)
        q, u = [x, y] + q, [ux, uy] + u
    else:
        foot = O
    l = a + b
    up = {st: -sp.sin(st) * N.x + sp.cos(st) * N.y, sw: -sp.sin(sw) * N.x + sp.cos(sw) * N.y}
    turn = {st: (-sp.cos(st) * N.x - sp.sin(st) * N.y) * w_st,
            sw: (-sp.cos(sw) * N.x - sp.sin(sw) * N.y) * w_sw}

    def point(name, base, length, leg):
        p = base.locatenew(name, length * up[leg])
        p.set_vel(N, base.vel(N) + length * turn[leg])
        return p

    leg_st, hip = point("leg_st", foot, a, st), point("hip", foot, l, st)
    leg_sw, swing = point("leg_sw", hip, -b, sw), point("swing_foot", hip, -l, sw)
    masses = [(leg_st, m), (hip, m_H), (leg_sw, m)]
    weight = g * (sp.sin(gamma) * N.x - sp.cos(gamma) * N.y)
    kane = me.KanesMethod(N, q, u, [qi.diff() - ui for qi, ui in zip(q, u, strict=True)])
    kane.kanes_equations([me.Particle(f"p{k}", p, mass) for k, (p, mass) in enumerate(masses)],
                         [(p, mass * weight) for p, mass in masses])
    return kane, N, swing, (st, sw), (w_st, w_sw)


def heel_strike():
    """The floating biped's impact at the swing foot (e = 0, stick): rigidimpact's map."""
    kane, N, swing, _, _ = legs(floating=True)
    strike = ri.mechanics.impact(kane, [ri.mechanics.contact(
        swing, N.y, restitution=0, tangential="stick", name="heel")], frame=N)
    return kane, strike, strike.solve()


def impact_map(solution, kane) -> sp.Matrix:
    """[stance, swing] rates after (relabelled) from before, at theta_st = -alpha,
    theta_sw = alpha (the legs symmetric about the slope's normal at heel strike)."""
    _, _, st, sw = kane.q
    ux, uy, w_st, w_sw = kane.u
    at = {st: -alpha, sw: alpha, ux: 0, uy: 0}
    after = solution.speeds_after.xreplace(at)
    rows = [after[3], after[2]]  # the old swing leg is the new stance leg
    return sp.Matrix([[sp.diff(r, w) for w in (w_st, w_sw)] for r in rows]).applyfunc(
        lambda x: sp.factor(sp.trigsimp(x)))


def gait(solution, kane, values=VALUES, guess=(0.27, -0.27, -1.1, -0.4)):
    """The period-one gait's fixed point (slope frame) and eigenvalues, from `guess`
    (near the stable gait, a long step)."""
    flow_kane, _, _, (st, sw), (w_st, w_sw) = legs(floating=False)
    rhs = ri.mechanics.flow_of(flow_kane, values)
    x_, y_, st_f, sw_f = kane.q
    ux, uy, w_st_f, w_sw_f = kane.u
    after = sp.lambdify([st_f, sw_f, w_st_f, w_sw_f],
                        list(solution.speeds_after.xreplace({ux: 0, uy: 0}).xreplace(values)),
                        "numpy", cse=True)

    def jump(x):
        _, lift, old_stance, old_swing = after(*x)
        if lift < -1e-9:
            raise ri.InputError("heel strike", "the old stance foot would be pulled into "
                                "the ground: it cannot leave")
        return np.array([x[1], x[0], old_swing, old_stance])

    biped = ri.mechanics.Hybrid(
        rhs, gap=lambda x: math.cos(x[0]) - math.cos(x[1]), jump=jump,
        guard=lambda x: x[1] > 0.05, fallen=lambda x: abs(x[0]) > 1.2)
    return biped.fixed_point(np.array(guess, float), free=[0, 2, 3],
                             complete=lambda x: np.array([x[0], -x[0], x[2], x[3]]))


def plain_recipe():
    """The baseline: the same map by the plain SymPy recipe (M from KanesMethod, J from
    partial velocities, the impact equations solved with Matrix.solve)."""
    kane, N, swing, _, _ = legs(floating=True)
    M = kane.mass_matrix
    u = sp.Matrix(kane.u)
    partials = me.partial_velocity([swing.vel(N)], list(kane.u), N)[0]
    J = sp.Matrix([[p.dot(N.y) for p in partials], [p.dot(N.x) for p in partials]])
    # unknowns (u+, P): M (u+ - u-) = J^T P, and the heel at rest after (e = 0, stick):
    # J u+ = 0
    A = sp.Matrix.vstack(sp.Matrix.hstack(M, -J.T), sp.Matrix.hstack(J, sp.zeros(2, 2)))
    rhs = sp.Matrix.vstack(M * u, sp.zeros(2, 1))
    return sp.Matrix(A.solve(rhs)[:4])


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--json", action="store_true")
    parser.add_argument("--baseline", action="store_true",
                        help="also time the plain SymPy recipe for the same map "
                             "(it did not finish in 20 minutes here)")
    args = parser.parse_args(argv)
    start = time.perf_counter()
    kane, strike, solution = heel_strike()
    H = impact_map(solution, kane)
    derived = time.perf_counter() - start
    found = gait(solution, kane)
    slope = float(VALUES[gamma])
    state = found.state - np.array([slope, slope, 0, 0])  # from the true vertical
    out = {"impact_map": str(H),
           "fixed_point": [float(x) for x in state],
           "eigenvalues": [[float(z.real), float(z.imag)] for z in found.eigenvalues],
           "stable": found.stable,
           "seconds": {"impact_map": round(derived, 2),
                       "total": round(time.perf_counter() - start, 2)}}
    if args.baseline:
        begin = time.perf_counter()
        plain = plain_recipe()
        out["seconds"]["plain_recipe"] = round(time.perf_counter() - begin, 2)
        kane_q = kane.q
        check = {kane_q[2]: -0.3, kane_q[3]: 0.3, **VALUES}
        difference = (plain.xreplace(check) - solution.speeds_after.xreplace(check)).xreplace(
            {w: k + 1 for k, w in enumerate(kane.u)})
        out["plain_recipe_agrees"] = bool(max(abs(float(x)) for x in difference) < 1e-12)
    if args.json:
        print(json.dumps(out, indent=2))
    else:
        print("Heel-strike map, [stance, swing] rates after = H [stance, swing] before:")
        sp.pprint(H)
        print("Period-one gait just after heel strike (rad, rad/s):", out["fixed_point"])
        print("Eigenvalues of the Poincare map:", out["eigenvalues"])
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
