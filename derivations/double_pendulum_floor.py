"""A double pendulum (two uniform rods hinged at O, one on the other) whose tip strikes
the floor with Coulomb friction, under the three restitution laws, built with
sympy.physics.mechanics and struck by rigidimpact.

The links (mass 1, length 1 each) hang from O at angles q1 = 0.6 and q2 = 0.8 rad from
the downward vertical, O being cos q1 + cos q2 above the floor; the tip meets the floor
moving down and sideways (rates u1 = -1, u2 = -2.5 rad/s), with e = 1 and mu = 0.7. The
friction is solved exactly by Routh's method along the impulse path, with Newton's,
Poisson's or the energetic restitution law. Where the slip reverses, Newton's law can
create kinetic energy (Kane and Levinson's paradox): rigidimpact says so in a warning
instead of reporting a gain silently.

``--json`` prints, for each law, the rates after, the impulses, the course of the slip,
the fraction of kinetic energy lost and the warnings.

Run: ``python derivations/double_pendulum_floor.py [--json]``.
"""

from __future__ import annotations

import argparse
import json

import sympy as sp
import sympy.physics.mechanics as me

import rigidimpact as ri

m1, m2, L1, L2 = sp.symbols("m_1 m_2 L_1 L_2", positive=True)
VALUES = {m1: 1, m2: 1, L1: 1, L2: 1}


def pendulum():
    """The double pendulum as a KanesMethod, with its tip point and frame."""
    q1, q2, u1, u2 = me.dynamicsymbols("q1 q2 u1 u2")
    N, A, B = (me.ReferenceFrame(n) for n in "NAB")
    A.orient_axis(N, N.z, q1)
    B.orient_axis(N, N.z, q2)
    A.set_ang_vel(N, u1 * N.z)
    B.set_ang_vel(N, u2 * N.z)
    O = me.Point("O")
    O.set_vel(N, 0)
    elbow = O.locatenew("elbow", -L1 * A.y)
    elbow.v2pt_theory(O, N, A)
    tip = elbow.locatenew("tip", -L2 * B.y)
    tip.v2pt_theory(elbow, N, B)
    centres = []
    for name, frame, base, length in (("c1", A, O, L1), ("c2", B, elbow, L2)):
        c = base.locatenew(name, -length / 2 * frame.y)
        c.v2pt_theory(base, N, frame)
        centres.append(c)
    rods = [me.RigidBody(f"rod{k}", c, f, mass, (me.inertia(f, 0, 0, mass * length**2 / 12), c))
            for k, (c, f, mass, length) in enumerate(((centres[0], A, m1, L1),
                                                      (centres[1], B, m2, L2)))]
    kane = me.KanesMethod(N, [q1, q2], [u1, u2], [q1.diff() - u1, q2.diff() - u2])
    kane.kanes_equations(rods, [])
    return kane, N, tip


# the tip at (sin q1 + sin q2, -cos q1 - cos q2) from O, moving at u1 (cos q1, sin q1) +
# u2 (cos q2, sin q2): down and to the left
STATE = {"q1": sp.Rational(3, 5), "q2": sp.Rational(4, 5), "u1": sp.Integer(-1),
         "u2": sp.Rational(-5, 2)}
FRICTION, RESTITUTION = sp.Rational(7, 10), sp.Integer(1)


def strike(law: str, kane=None, N=None, tip=None) -> ri.Solution:
    """The tip's impact on the floor under `law` at the state above (numbers)."""
    if kane is None:
        kane, N, tip = pendulum()
    q1, q2 = kane.q
    hit = ri.mechanics.impact(kane, [ri.mechanics.contact(
        tip, N.y, restitution=RESTITUTION, tangential="coulomb", friction=FRICTION,
        law=law, name="tip")], frame=N)
    at = {q1: sp.Float(STATE["q1"], 30), q2: sp.Float(STATE["q2"], 30), **VALUES}
    numbers = hit.at(at)
    u1, u2 = kane.u
    speeds = {u1: STATE["u1"], u2: STATE["u2"]}
    return numbers.at(speeds).solve()


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--json", action="store_true")
    args = parser.parse_args(argv)
    kane, N, tip = pendulum()
    out = {}
    for law in ("newton", "poisson", "energetic"):
        solved = strike(law, kane, N, tip)
        normal, along = solved.contact_impulse
        out[law] = {"u1": float(solved.speeds_after[0]), "u2": float(solved.speeds_after[1]),
                    "normal_impulse": float(normal), "tangential_impulse": float(along),
                    "course": solved.regime,
                    "energy_lost": float(solved.energy_lost),
                    "warnings": list(solved.warnings)}
    if args.json:
        print(json.dumps(out, indent=2))
    else:
        for law, r in out.items():
            print(f"{law:>9}: u1 = {r['u1']:.6f}, u2 = {r['u2']:.6f}, P_n = "
                  f"{r['normal_impulse']:.6f}, P_t = {r['tangential_impulse']:.6f}, "
                  f"{r['course']}, energy lost {r['energy_lost']:.6f}")
            for w in r["warnings"]:
                print(f"           warning: {w}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
